#include "gpu/presenter.h"

#include <algorithm>
#include <string>

#include "gpu/buffer.h"
#include "gpu/device.h"
#include "gpu/error.h"

namespace ddish::gpu {

namespace {

// 5 s: a CPU device presenting a full-size panel is slow, not hung.
constexpr std::uint64_t kTimeoutNs = 5'000'000'000ull;

void swapchain_barrier(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to,
                       VkPipelineStageFlags src_stage, VkAccessFlags src_access,
                       VkPipelineStageFlags dst_stage, VkAccessFlags dst_access) {
  VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  b.srcAccessMask = src_access;
  b.dstAccessMask = dst_access;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  vkCmdPipelineBarrier(cmd, src_stage, dst_stage, 0, 0, nullptr, 0, nullptr, 1, &b);
}

DeviceHandle<VkSemaphore, vkDestroySemaphore> make_semaphore(const Device& device) {
  VkSemaphoreCreateInfo info{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  VkSemaphore s = VK_NULL_HANDLE;
  check(vkCreateSemaphore(device.handle(), &info, nullptr, &s), "vkCreateSemaphore");
  return {device.handle(), s};
}

}  // namespace

PresentPlacement place_frame(std::uint32_t frame_w, std::uint32_t frame_h, std::uint32_t target_w,
                             std::uint32_t target_h) {
  PresentPlacement p;
  if (frame_w <= target_w && frame_h <= target_h) {
    p.width = frame_w;
    p.height = frame_h;
  } else {
    // The larger of the two reductions decides; integer maths so a side never exceeds the target.
    if (std::uint64_t(frame_w) * target_h >= std::uint64_t(frame_h) * target_w) {
      p.width = target_w;
      p.height = std::max<std::uint32_t>(1, std::uint32_t(std::uint64_t(frame_h) * target_w / frame_w));
    } else {
      p.height = target_h;
      p.width = std::max<std::uint32_t>(1, std::uint32_t(std::uint64_t(frame_w) * target_h / frame_h));
    }
    p.scaled = true;
  }
  p.x = std::int32_t((target_w - p.width) / 2);
  p.y = std::int32_t((target_h - p.height) / 2);
  return p;
}

Presenter::Presenter(const Device& device, VkSurfaceKHR surface, VkExtent2D drawable, bool mailbox)
    : device_(device),
      drawable_(drawable),
      swapchain_(std::make_unique<Swapchain>(device, surface, drawable, mailbox)) {
  VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pool_info.queueFamilyIndex = device.queue_family();
  VkCommandPool pool = VK_NULL_HANDLE;
  check(vkCreateCommandPool(device.handle(), &pool_info, nullptr, &pool), "vkCreateCommandPool");
  pool_ = {device.handle(), pool};
  VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  alloc.commandPool = pool;
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  check(vkAllocateCommandBuffers(device.handle(), &alloc, &cmd_), "vkAllocateCommandBuffers");
  VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VkFence fence = VK_NULL_HANDLE;
  check(vkCreateFence(device.handle(), &fence_info, nullptr, &fence), "vkCreateFence");
  fence_ = {device.handle(), fence};
  acquired_ = make_semaphore(device);
  for (std::size_t i = 0; i < swapchain_->images().size(); ++i)
    rendered_.push_back(make_semaphore(device));
}

Presenter::~Presenter() {
  // Nothing of ours may still be in use when the handles go (each present waited for its
  // submission, but the presentation engine may hold the semaphores a little longer).
  vkQueueWaitIdle(device_.queue());
}

void Presenter::resize(VkExtent2D drawable) {
  drawable_ = drawable;
  stale_ = true;
}

void Presenter::rebuild() {
  check(vkQueueWaitIdle(device_.queue()), "vkQueueWaitIdle");
  swapchain_->recreate(drawable_);
  stale_ = false;
  rendered_.clear();
  for (std::size_t i = 0; i < swapchain_->images().size(); ++i)
    rendered_.push_back(make_semaphore(device_));
}

void Presenter::ensure_frame_image(std::uint32_t width, std::uint32_t height) {
  if (frame_image_.handle() != VK_NULL_HANDLE && frame_image_.desc().width == width &&
      frame_image_.desc().height == height)
    return;
  frame_image_ = Image(device_, ImageDesc{.width = width,
                                          .height = height,
                                          .format = VK_FORMAT_R8G8B8A8_UNORM,
                                          .usage = VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                                                   VK_IMAGE_USAGE_TRANSFER_DST_BIT});
}

PresentStatus Presenter::present(const Buffer& frame, std::uint32_t width, std::uint32_t height,
                                 const std::function<void(VkCommandBuffer)>& before) {
  if (VkDeviceSize(width) * height * 4 > frame.size())
    throw GpuError("a frame of " + std::to_string(width) + "x" + std::to_string(height) +
                   " does not fit its buffer of " + std::to_string(frame.size()) + " bytes");
  if (stale_ || !swapchain_->valid()) {
    stale_ = true;
    rebuild();
    if (!swapchain_->valid()) return PresentStatus::minimised;
  }
  std::uint32_t index = 0;
  const VkResult acquired = vkAcquireNextImageKHR(device_.handle(), swapchain_->handle(), kTimeoutNs,
                                                  acquired_.get(), VK_NULL_HANDLE, &index);
  if (acquired == VK_ERROR_OUT_OF_DATE_KHR) {
    stale_ = true;
    rebuild();
    return swapchain_->valid() ? PresentStatus::out_of_date : PresentStatus::minimised;
  }
  if (acquired == VK_TIMEOUT) throw GpuError("no swapchain image within 5 s (vkAcquireNextImageKHR)");
  if (acquired != VK_SUBOPTIMAL_KHR) check(acquired, "vkAcquireNextImageKHR");
  ensure_frame_image(width, height);

  check(vkResetCommandBuffer(cmd_, 0), "vkResetCommandBuffer");
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  check(vkBeginCommandBuffer(cmd_, &begin), "vkBeginCommandBuffer");
  if (before) before(cmd_);

  // The frame into the persistent image (the last frame's blit read it: the barrier orders).
  image_barrier(cmd_, frame_image_, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT,
                VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {width, height, 1};
  vkCmdCopyBufferToImage(cmd_, frame.handle(), frame_image_.handle(),
                         VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
  image_barrier(cmd_, frame_image_, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT,
                VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                VK_ACCESS_TRANSFER_READ_BIT);

  const VkImage target = swapchain_->images()[index];
  const VkExtent2D extent = swapchain_->extent();
  swapchain_barrier(cmd_, target, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                    VK_PIPELINE_STAGE_TRANSFER_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT,
                    VK_ACCESS_TRANSFER_WRITE_BIT);
  const VkClearColorValue black{{0.0f, 0.0f, 0.0f, 1.0f}};
  const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  vkCmdClearColorImage(cmd_, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &black, 1, &range);
  swapchain_barrier(cmd_, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                    VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT,
                    VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                    VK_ACCESS_TRANSFER_WRITE_BIT);
  placement_ = place_frame(width, height, extent.width, extent.height);
  VkImageBlit blit{};
  blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  blit.srcOffsets[1] = {std::int32_t(width), std::int32_t(height), 1};
  blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  blit.dstOffsets[0] = {placement_.x, placement_.y, 0};
  blit.dstOffsets[1] = {placement_.x + std::int32_t(placement_.width),
                        placement_.y + std::int32_t(placement_.height), 1};
  vkCmdBlitImage(cmd_, frame_image_.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target,
                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit,
                 placement_.scaled ? VK_FILTER_LINEAR : VK_FILTER_NEAREST);
  swapchain_barrier(cmd_, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                    VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_PIPELINE_STAGE_TRANSFER_BIT,
                    VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 0);
  check(vkEndCommandBuffer(cmd_), "vkEndCommandBuffer");

  const VkPipelineStageFlags wait_stage = VK_PIPELINE_STAGE_TRANSFER_BIT;
  const VkSemaphore wait = acquired_.get();
  const VkSemaphore signal = rendered_[index].get();
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.waitSemaphoreCount = 1;
  submit.pWaitSemaphores = &wait;
  submit.pWaitDstStageMask = &wait_stage;
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd_;
  submit.signalSemaphoreCount = 1;
  submit.pSignalSemaphores = &signal;
  const VkFence fence = fence_.get();
  check(vkResetFences(device_.handle(), 1, &fence), "vkResetFences");
  check(vkQueueSubmit(device_.queue(), 1, &submit, fence), "vkQueueSubmit");

  VkPresentInfoKHR info{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
  info.waitSemaphoreCount = 1;
  info.pWaitSemaphores = &signal;
  const VkSwapchainKHR sc = swapchain_->handle();
  info.swapchainCount = 1;
  info.pSwapchains = &sc;
  info.pImageIndices = &index;
  const VkResult shown = vkQueuePresentKHR(device_.queue(), &info);
  const VkResult waited = vkWaitForFences(device_.handle(), 1, &fence, VK_TRUE, kTimeoutNs * 12);
  if (waited == VK_TIMEOUT) throw GpuError("presenting a frame did not finish within 60 s");
  check(waited, "vkWaitForFences");
  if (shown == VK_ERROR_OUT_OF_DATE_KHR || shown == VK_SUBOPTIMAL_KHR || acquired == VK_SUBOPTIMAL_KHR) {
    stale_ = true;  // shown or not, the next frame gets a swapchain of the right size
    return shown == VK_ERROR_OUT_OF_DATE_KHR ? PresentStatus::out_of_date : PresentStatus::presented;
  }
  check(shown, "vkQueuePresentKHR");
  return PresentStatus::presented;
}

}  // namespace ddish::gpu
