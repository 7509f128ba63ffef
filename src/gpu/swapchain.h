// A VkSwapchainKHR on a surface someone else made (the window module's SDL surface): gpu/ knows
// no window system. Images are what the presenter (gpu/presenter.h) copies a finished frame
// into, so they are made for transfers: usage TRANSFER_DST, a UNORM 8-bit format (the frame
// is already sRGB-encoded; an _SRGB format would encode it twice), opaque.
// Present mode: FIFO (always there, vsync), or MAILBOX when asked for and offered.
#pragma once

#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

namespace ddish::gpu {

class Device;

// Whether the device's queue family can present to `surface` (a GPU may render on a queue that
// cannot show the window).
bool can_present(const Device& device, VkSurfaceKHR surface);

class Swapchain {
 public:
  // `wanted` is the window's drawable size, used where the surface leaves the size to us.
  // Throws GpuError when the queue cannot present to the surface or no format fits.
  Swapchain(const Device& device, VkSurfaceKHR surface, VkExtent2D wanted, bool mailbox);
  ~Swapchain();
  Swapchain(const Swapchain&) = delete;
  Swapchain& operator=(const Swapchain&) = delete;

  // Makes the swapchain again for the surface's current size (after a resize, or when
  // presenting said out of date); the old one is retired through oldSwapchain. The caller must
  // have waited for the images' last use. Returns false and keeps no swapchain while the
  // surface has no area (a minimised window); call again later.
  bool recreate(VkExtent2D wanted);

  VkSwapchainKHR handle() const { return swapchain_; }
  bool valid() const { return swapchain_ != VK_NULL_HANDLE; }
  VkFormat format() const { return format_; }
  VkExtent2D extent() const { return extent_; }
  VkPresentModeKHR present_mode() const { return present_mode_; }
  const std::vector<VkImage>& images() const { return images_; }

 private:
  const Device& device_;
  VkSurfaceKHR surface_;
  bool mailbox_;
  VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
  VkFormat format_ = VK_FORMAT_UNDEFINED;
  VkColorSpaceKHR color_space_ = VK_COLOR_SPACE_SRGB_NONLINEAR_KHR;
  VkExtent2D extent_{0, 0};
  VkPresentModeKHR present_mode_ = VK_PRESENT_MODE_FIFO_KHR;
  std::vector<VkImage> images_;
};

}  // namespace ddish::gpu
