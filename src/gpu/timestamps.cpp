#include "gpu/timestamps.h"

#include <string>

#include "gpu/device.h"
#include "gpu/error.h"

namespace ddish::gpu {

TimestampQueries::TimestampQueries(const Device& device, std::uint32_t ranges)
    : device_(device.handle()), ranges_(ranges) {
  const DeviceInfo& info = device.info();
  if (!info.timestamps_supported())
    throw GpuError("Vulkan device " + info.name + " cannot write timestamps on its queue");
  if (ranges == 0) throw GpuError("a timestamp query pool needs at least one range");
  tick_mask_ = info.timestamp_valid_bits >= 64 ? ~std::uint64_t{0}
                                               : (std::uint64_t{1} << info.timestamp_valid_bits) - 1;
  ns_per_tick_ = static_cast<double>(info.timestamp_period);

  VkQueryPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  pool_info.queryType = VK_QUERY_TYPE_TIMESTAMP;
  pool_info.queryCount = 2 * ranges;
  VkQueryPool pool = VK_NULL_HANDLE;
  check(vkCreateQueryPool(device_, &pool_info, nullptr, &pool), "vkCreateQueryPool");
  pool_ = {device_, pool};
}

void TimestampQueries::check_range(std::uint32_t range) const {
  if (range >= ranges_)
    throw GpuError("timestamp range " + std::to_string(range) + " out of " +
                   std::to_string(ranges_));
}

double TimestampQueries::to_ms(std::uint64_t begin, std::uint64_t end) const {
  // Masked subtraction survives a counter that wrapped between the two writes.
  return static_cast<double>((end - begin) & tick_mask_) * ns_per_tick_ * 1e-6;
}

void TimestampQueries::reset(VkCommandBuffer cmd) const {
  vkCmdResetQueryPool(cmd, pool_.get(), 0, 2 * ranges_);
}

void TimestampQueries::begin(VkCommandBuffer cmd, std::uint32_t range) const {
  check_range(range);
  vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, pool_.get(), 2 * range);
}

void TimestampQueries::end(VkCommandBuffer cmd, std::uint32_t range) const {
  check_range(range);
  vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool_.get(), 2 * range + 1);
}

double TimestampQueries::milliseconds(std::uint32_t range) const {
  check_range(range);
  std::uint64_t ticks[2] = {0, 0};
  check(vkGetQueryPoolResults(device_, pool_.get(), 2 * range, 2, sizeof(ticks), ticks,
                              sizeof(std::uint64_t),
                              VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
        "vkGetQueryPoolResults");
  return to_ms(ticks[0], ticks[1]);
}

std::vector<double> TimestampQueries::all_milliseconds() const {
  std::vector<std::uint64_t> ticks(2 * static_cast<std::size_t>(ranges_));
  check(vkGetQueryPoolResults(device_, pool_.get(), 0, 2 * ranges_,
                              ticks.size() * sizeof(std::uint64_t), ticks.data(),
                              sizeof(std::uint64_t),
                              VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
        "vkGetQueryPoolResults");
  std::vector<double> ms(ranges_);
  for (std::uint32_t r = 0; r < ranges_; ++r)
    ms[r] = to_ms(ticks[2 * r], ticks[2 * r + 1]);
  return ms;
}

}  // namespace ddish::gpu
