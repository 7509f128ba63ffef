// GPU time of recorded ranges, from timestamp queries. Each range is a pair of timestamps: one
// written when the work before it has started, one when it has finished; their difference in
// ticks times the device's timestampPeriod is the GPU time in nanoseconds.
//
//   TimestampQueries timer(device, 1);
//   runner.run([&](VkCommandBuffer cmd) {
//     timer.reset(cmd);
//     timer.begin(cmd, 0);
//     ... work ...
//     timer.end(cmd, 0);
//   });
//   double ms = timer.milliseconds(0);
#pragma once

#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

#include "gpu/handle.h"

namespace ddish::gpu {

class Device;

class TimestampQueries {
 public:
  // Throws GpuError when the device's queue cannot write timestamps
  // (check device.info().timestamps_supported() first to run without timings).
  TimestampQueries(const Device& device, std::uint32_t ranges);

  std::uint32_t ranges() const { return ranges_; }

  // Resets every query; recorded before the first begin() in the same or an earlier submission,
  // outside any render pass.
  void reset(VkCommandBuffer cmd) const;
  // The start of range r: once all earlier commands have reached the top of the pipe.
  void begin(VkCommandBuffer cmd, std::uint32_t range) const;
  // The end of range r: once all earlier commands have completed every stage.
  void end(VkCommandBuffer cmd, std::uint32_t range) const;

  // The GPU time of range r in milliseconds: finite and >= 0. Waits for the results, so the
  // submission must have been made. Throws GpuError for a range out of bounds.
  double milliseconds(std::uint32_t range) const;
  // All ranges at once (one query readback).
  std::vector<double> all_milliseconds() const;

 private:
  void check_range(std::uint32_t range) const;
  double to_ms(std::uint64_t begin_ticks, std::uint64_t end_ticks) const;

  VkDevice device_ = VK_NULL_HANDLE;
  DeviceHandle<VkQueryPool, vkDestroyQueryPool> pool_;
  std::uint32_t ranges_ = 0;
  std::uint64_t tick_mask_ = 0;    // timestampValidBits low bits are meaningful
  double ns_per_tick_ = 0.0;
};

}  // namespace ddish::gpu
