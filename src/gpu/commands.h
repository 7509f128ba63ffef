// Recording and submitting command buffers. CommandRunner is the simple path: record into one
// command buffer, submit it, wait on a fence. That is what uploads, tests and the one-frame-at-a-
// time renderer need; frames in flight, if ever wanted, would get their own class.
#pragma once

#include <cstdint>
#include <functional>

#include <vulkan/vulkan.h>

#include "gpu/handle.h"

namespace ddish::gpu {

class Device;

class CommandRunner {
 public:
  explicit CommandRunner(const Device& device);

  // Records with `record` into a fresh primary command buffer, submits it to the device's queue
  // and blocks until it has finished. Throws GpuError on failure, or when the GPU does not finish
  // within `timeout_ns` (a hung or lost device), and rethrows what `record` throws (nothing is
  // submitted then). Not thread safe: one runner per thread.
  void run(const std::function<void(VkCommandBuffer)>& record,
           std::uint64_t timeout_ns = kDefaultTimeoutNs);

  // 10 min: a CPU device drawing a 48-view quilt of a 262k-triangle scene in one submission can
  // take over a minute on a loaded 2-core machine; the timeout exists to catch hangs, not slowness.
  static constexpr std::uint64_t kDefaultTimeoutNs = 600'000'000'000ull;

 private:
  const Device* device_;
  DeviceHandle<VkCommandPool, vkDestroyCommandPool> pool_;
  DeviceHandle<VkFence, vkDestroyFence> fence_;
  VkCommandBuffer command_buffer_ = VK_NULL_HANDLE;  // freed with the pool
};

// A global memory barrier: everything `src_access` did in `src_stage` before it is visible to
// `dst_access` in `dst_stage` after it. E.g. compute-shader writes -> host reads before a
// readback, or transfer writes -> vertex input after an upload.
void memory_barrier(VkCommandBuffer cmd, VkPipelineStageFlags src_stage, VkAccessFlags src_access,
                    VkPipelineStageFlags dst_stage, VkAccessFlags dst_access);

}  // namespace ddish::gpu
