#include "gpu/swapchain.h"

#include <algorithm>

#include "gpu/device.h"
#include "gpu/error.h"

namespace ddish::gpu {

namespace {

// The formats a frame of packed RGBA8 display values can be blitted into unchanged.
bool unorm8(VkFormat f) { return f == VK_FORMAT_B8G8R8A8_UNORM || f == VK_FORMAT_R8G8B8A8_UNORM; }

}  // namespace

bool can_present(const Device& device, VkSurfaceKHR surface) {
  VkBool32 supported = VK_FALSE;
  check(vkGetPhysicalDeviceSurfaceSupportKHR(device.physical(), device.queue_family(), surface,
                                             &supported),
        "vkGetPhysicalDeviceSurfaceSupportKHR");
  return supported == VK_TRUE;
}

Swapchain::Swapchain(const Device& device, VkSurfaceKHR surface, VkExtent2D wanted, bool mailbox)
    : device_(device), surface_(surface), mailbox_(mailbox) {
  if (!can_present(device, surface))
    throw GpuError("the Vulkan device " + device.info().name +
                   " cannot present to the window's surface (its queue family has no present support)");
  std::uint32_t count = 0;
  check(vkGetPhysicalDeviceSurfaceFormatsKHR(device.physical(), surface, &count, nullptr),
        "vkGetPhysicalDeviceSurfaceFormatsKHR");
  std::vector<VkSurfaceFormatKHR> formats(count);
  check(vkGetPhysicalDeviceSurfaceFormatsKHR(device.physical(), surface, &count, formats.data()),
        "vkGetPhysicalDeviceSurfaceFormatsKHR");
  for (const VkSurfaceFormatKHR& f : formats) {
    VkFormatProperties props{};
    vkGetPhysicalDeviceFormatProperties(device.physical(), f.format, &props);
    if (unorm8(f.format) && (props.optimalTilingFeatures & VK_FORMAT_FEATURE_BLIT_DST_BIT)) {
      format_ = f.format;
      color_space_ = f.colorSpace;
      break;
    }
  }
  if (format_ == VK_FORMAT_UNDEFINED)
    throw GpuError("the window's surface offers no 8-bit UNORM format to blit into");

  count = 0;
  check(vkGetPhysicalDeviceSurfacePresentModesKHR(device.physical(), surface, &count, nullptr),
        "vkGetPhysicalDeviceSurfacePresentModesKHR");
  std::vector<VkPresentModeKHR> modes(count);
  check(vkGetPhysicalDeviceSurfacePresentModesKHR(device.physical(), surface, &count, modes.data()),
        "vkGetPhysicalDeviceSurfacePresentModesKHR");
  if (mailbox_ && std::find(modes.begin(), modes.end(), VK_PRESENT_MODE_MAILBOX_KHR) != modes.end())
    present_mode_ = VK_PRESENT_MODE_MAILBOX_KHR;
  recreate(wanted);
}

Swapchain::~Swapchain() {
  if (swapchain_ != VK_NULL_HANDLE) vkDestroySwapchainKHR(device_.handle(), swapchain_, nullptr);
}

bool Swapchain::recreate(VkExtent2D wanted) {
  VkSurfaceCapabilitiesKHR caps{};
  check(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(device_.physical(), surface_, &caps),
        "vkGetPhysicalDeviceSurfaceCapabilitiesKHR");
  VkExtent2D extent = caps.currentExtent;
  if (extent.width == 0xFFFFFFFFu) {  // the surface takes the swapchain's size
    extent.width = std::clamp(wanted.width, caps.minImageExtent.width, caps.maxImageExtent.width);
    extent.height = std::clamp(wanted.height, caps.minImageExtent.height, caps.maxImageExtent.height);
  }
  VkSwapchainKHR old = swapchain_;
  swapchain_ = VK_NULL_HANDLE;
  images_.clear();
  if (extent.width == 0 || extent.height == 0) {  // minimised: nothing to present to
    if (old != VK_NULL_HANDLE) vkDestroySwapchainKHR(device_.handle(), old, nullptr);
    extent_ = extent;
    return false;
  }
  if (!(caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT)) {
    if (old != VK_NULL_HANDLE) vkDestroySwapchainKHR(device_.handle(), old, nullptr);
    throw GpuError("the window's surface cannot take transfers into its images");
  }
  std::uint32_t image_count = caps.minImageCount + 1;
  if (caps.maxImageCount > 0) image_count = std::min(image_count, caps.maxImageCount);

  VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
  info.surface = surface_;
  info.minImageCount = image_count;
  info.imageFormat = format_;
  info.imageColorSpace = color_space_;
  info.imageExtent = extent;
  info.imageArrayLayers = 1;
  info.imageUsage = VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.preTransform = (caps.supportedTransforms & VK_SURFACE_TRANSFORM_IDENTITY_BIT_KHR)
                          ? VK_SURFACE_TRANSFORM_IDENTITY_BIT_KHR
                          : caps.currentTransform;
  info.compositeAlpha = (caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR)
                            ? VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR
                            : VK_COMPOSITE_ALPHA_INHERIT_BIT_KHR;
  info.presentMode = present_mode_;
  info.clipped = VK_TRUE;
  info.oldSwapchain = old;
  const VkResult made = vkCreateSwapchainKHR(device_.handle(), &info, nullptr, &swapchain_);
  if (old != VK_NULL_HANDLE) vkDestroySwapchainKHR(device_.handle(), old, nullptr);
  check(made, "vkCreateSwapchainKHR");
  extent_ = extent;
  std::uint32_t n = 0;
  check(vkGetSwapchainImagesKHR(device_.handle(), swapchain_, &n, nullptr), "vkGetSwapchainImagesKHR");
  images_.resize(n);
  check(vkGetSwapchainImagesKHR(device_.handle(), swapchain_, &n, images_.data()),
        "vkGetSwapchainImagesKHR");
  return true;
}

}  // namespace ddish::gpu
