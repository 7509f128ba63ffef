#include "gpu/commands.h"

#include <string>

#include "gpu/device.h"
#include "gpu/error.h"

namespace ddish::gpu {

CommandRunner::CommandRunner(const Device& device) : device_(&device) {
  VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  // The one command buffer is re-recorded for each run, so it must be individually resettable.
  pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT |
                    VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
  pool_info.queueFamilyIndex = device.queue_family();
  VkCommandPool pool = VK_NULL_HANDLE;
  check(vkCreateCommandPool(device.handle(), &pool_info, nullptr, &pool), "vkCreateCommandPool");
  pool_ = DeviceHandle<VkCommandPool, vkDestroyCommandPool>(device.handle(), pool);

  VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  alloc.commandPool = pool;
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  check(vkAllocateCommandBuffers(device.handle(), &alloc, &command_buffer_),
        "vkAllocateCommandBuffers");

  VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VkFence fence = VK_NULL_HANDLE;
  check(vkCreateFence(device.handle(), &fence_info, nullptr, &fence), "vkCreateFence");
  fence_ = DeviceHandle<VkFence, vkDestroyFence>(device.handle(), fence);
}

void CommandRunner::run(const std::function<void(VkCommandBuffer)>& record,
                        std::uint64_t timeout_ns) {
  check(vkResetCommandBuffer(command_buffer_, 0), "vkResetCommandBuffer");
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  check(vkBeginCommandBuffer(command_buffer_, &begin), "vkBeginCommandBuffer");
  try {
    record(command_buffer_);
  } catch (...) {
    // Leave the buffer in a state the next run can reset: end it, never submit it.
    vkEndCommandBuffer(command_buffer_);
    throw;
  }
  check(vkEndCommandBuffer(command_buffer_), "vkEndCommandBuffer");

  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &command_buffer_;
  VkFence fence = fence_.get();
  check(vkResetFences(device_->handle(), 1, &fence), "vkResetFences");
  check(vkQueueSubmit(device_->queue(), 1, &submit, fence), "vkQueueSubmit");
  VkResult waited = vkWaitForFences(device_->handle(), 1, &fence, VK_TRUE, timeout_ns);
  if (waited == VK_TIMEOUT) {
    // The command buffer is still pending: wait for good before anything reuses or frees it.
    vkDeviceWaitIdle(device_->handle());
    throw GpuError("GPU work did not finish within " + std::to_string(timeout_ns / 1'000'000) +
                   " ms");
  }
  check(waited, "vkWaitForFences");
}

void memory_barrier(VkCommandBuffer cmd, VkPipelineStageFlags src_stage, VkAccessFlags src_access,
                    VkPipelineStageFlags dst_stage, VkAccessFlags dst_access) {
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  barrier.srcAccessMask = src_access;
  barrier.dstAccessMask = dst_access;
  vkCmdPipelineBarrier(cmd, src_stage, dst_stage, 0, 1, &barrier, 0, nullptr, 0, nullptr);
}

}  // namespace ddish::gpu
