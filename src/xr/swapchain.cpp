#include "xr/swapchain.h"

#include <algorithm>
#include <stdexcept>

#include <openxr/openxr_platform.h>

#include "xr/error.h"

namespace ddish::xr {

EyeSwapchain::EyeSwapchain(XrSession session, std::uint32_t width, std::uint32_t height)
    : width_(width), height_(height) {
  std::uint32_t n = 0;
  check(xrEnumerateSwapchainFormats(session, 0, &n, nullptr), "xrEnumerateSwapchainFormats");
  std::vector<std::int64_t> formats(n);
  check(xrEnumerateSwapchainFormats(session, n, &n, formats.data()), "xrEnumerateSwapchainFormats");
  if (std::find(formats.begin(), formats.end(), kSwapchainFormat) == formats.end())
    throw std::runtime_error("xr: the runtime offers no VK_FORMAT_R8G8B8A8_SRGB swapchain");
  XrSwapchainCreateInfo ci{XR_TYPE_SWAPCHAIN_CREATE_INFO};
  ci.usageFlags = XR_SWAPCHAIN_USAGE_TRANSFER_DST_BIT | XR_SWAPCHAIN_USAGE_COLOR_ATTACHMENT_BIT;
  ci.format = kSwapchainFormat;
  ci.sampleCount = 1;
  ci.width = width;
  ci.height = height;
  ci.faceCount = 1;
  ci.arraySize = 1;
  ci.mipCount = 1;
  check(xrCreateSwapchain(session, &ci, &swapchain_), "xrCreateSwapchain");
  try {
    check(xrEnumerateSwapchainImages(swapchain_, 0, &n, nullptr), "xrEnumerateSwapchainImages");
    std::vector<XrSwapchainImageVulkan2KHR> images(n, {XR_TYPE_SWAPCHAIN_IMAGE_VULKAN2_KHR});
    check(xrEnumerateSwapchainImages(swapchain_, n, &n, reinterpret_cast<XrSwapchainImageBaseHeader*>(images.data())),
          "xrEnumerateSwapchainImages");
    for (const auto& i : images) images_.push_back(i.image);
  } catch (...) {
    xrDestroySwapchain(swapchain_);
    throw;
  }
}

EyeSwapchain::~EyeSwapchain() {
  if (swapchain_ != XR_NULL_HANDLE) xrDestroySwapchain(swapchain_);
}

XrResult EyeSwapchain::acquire() {
  XrSwapchainImageAcquireInfo ai{XR_TYPE_SWAPCHAIN_IMAGE_ACQUIRE_INFO};
  std::uint32_t index = 0;
  check(xrAcquireSwapchainImage(swapchain_, &ai, &index), "xrAcquireSwapchainImage");
  XrSwapchainImageWaitInfo wi{XR_TYPE_SWAPCHAIN_IMAGE_WAIT_INFO};
  wi.timeout = XR_INFINITE_DURATION;
  const XrResult r = check(xrWaitSwapchainImage(swapchain_, &wi), "xrWaitSwapchainImage");
  if (r == XR_TIMEOUT_EXPIRED) throw std::runtime_error("xr: xrWaitSwapchainImage timed out");
  acquired_ = index;
  return r;
}

void EyeSwapchain::record_copy(VkCommandBuffer cmd, VkBuffer buffer, VkDeviceSize offset) const {
  if (!acquired_) throw std::logic_error("xr: copy into a swapchain image that is not acquired");
  const VkImage image = images_.at(*acquired_);
  VkImageMemoryBarrier to_dst{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  to_dst.srcAccessMask = 0;  // the runtime is done with it: xrWaitSwapchainImage returned
  to_dst.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  to_dst.oldLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  to_dst.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  to_dst.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  to_dst.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  to_dst.image = image;
  to_dst.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0,
                       nullptr, 1, &to_dst);
  VkBufferImageCopy region{};
  region.bufferOffset = offset;
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {width_, height_, 1};
  vkCmdCopyBufferToImage(cmd, buffer, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
  VkImageMemoryBarrier back = to_dst;
  back.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  back.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  back.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  back.newLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, 0, 0,
                       nullptr, 0, nullptr, 1, &back);
}

XrResult EyeSwapchain::release() {
  XrSwapchainImageReleaseInfo ri{XR_TYPE_SWAPCHAIN_IMAGE_RELEASE_INFO};
  acquired_.reset();
  return check(xrReleaseSwapchainImage(swapchain_, &ri), "xrReleaseSwapchainImage");
}

}  // namespace ddish::xr
