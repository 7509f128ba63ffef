// One eye's OpenXR swapchain of sRGB RGBA8 images, and the copy of a rendered view into its
// acquired image. The Vulkan binding's layout rule: an image comes from xrWaitSwapchainImage in
// VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL and must go back to xrReleaseSwapchainImage in it, so
// the copy is recorded as COLOR_ATTACHMENT_OPTIMAL -> TRANSFER_DST_OPTIMAL, the copy,
// TRANSFER_DST_OPTIMAL -> COLOR_ATTACHMENT_OPTIMAL.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <vulkan/vulkan.h>
#include <openxr/openxr.h>

namespace ddish::xr {

// VK_FORMAT_R8G8B8A8_SRGB: the renderer's display buffer is sRGB-encoded RGBA8 bytes, so a plain
// buffer-to-image copy into an sRGB image shows exactly the values `ddish render` writes.
inline constexpr std::int64_t kSwapchainFormat = VK_FORMAT_R8G8B8A8_SRGB;

class EyeSwapchain {
 public:
  // Throws std::runtime_error when the runtime offers no R8G8B8A8_SRGB swapchains.
  EyeSwapchain(XrSession session, std::uint32_t width, std::uint32_t height);
  ~EyeSwapchain();
  EyeSwapchain(const EyeSwapchain&) = delete;
  EyeSwapchain& operator=(const EyeSwapchain&) = delete;

  XrSwapchain handle() const { return swapchain_; }
  std::uint32_t width() const { return width_; }
  std::uint32_t height() const { return height_; }
  bool acquired() const { return acquired_.has_value(); }

  // xrAcquireSwapchainImage + xrWaitSwapchainImage; returns the result of the wait (a success
  // code such as XR_SESSION_LOSS_PENDING is the caller's).
  XrResult acquire();
  // Records the copy of width x height packed RGBA8 pixels at `offset` of `buffer` (row 0 at
  // the top) into the acquired image; `buffer`'s writes must already be visible to transfers.
  void record_copy(VkCommandBuffer cmd, VkBuffer buffer, VkDeviceSize offset) const;
  // xrReleaseSwapchainImage (after the copy's submission has finished).
  XrResult release();

 private:
  XrSwapchain swapchain_ = XR_NULL_HANDLE;
  std::uint32_t width_ = 0;
  std::uint32_t height_ = 0;
  std::vector<VkImage> images_;
  std::optional<std::uint32_t> acquired_;
};

}  // namespace ddish::xr
