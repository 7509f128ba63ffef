#include "xr/vulkan_binding.h"

#include <string>

#include <vulkan/vulkan.h>
#include <openxr/openxr.h>
#include <openxr/openxr_platform.h>

#include "gpu/instance.h"
#include "xr/error.h"
#include "xr/instance.h"

namespace ddish::xr {

namespace {

std::string version(XrVersion v) {
  return std::to_string(XR_VERSION_MAJOR(v)) + "." + std::to_string(XR_VERSION_MINOR(v));
}

}  // namespace

void bind_vulkan(const Instance& xr, gpu::ContextOptions& options) {
  auto requirements = xr.function<PFN_xrGetVulkanGraphicsRequirements2KHR>("xrGetVulkanGraphicsRequirements2KHR");
  XrGraphicsRequirementsVulkan2KHR req{XR_TYPE_GRAPHICS_REQUIREMENTS_VULKAN2_KHR};
  check(requirements(xr.handle(), xr.system(), &req), "xrGetVulkanGraphicsRequirements2KHR");
  const XrVersion ours = XR_MAKE_VERSION(VK_API_VERSION_MAJOR(gpu::kRequiredApiVersion),
                                         VK_API_VERSION_MINOR(gpu::kRequiredApiVersion), 0);
  if (ours < XR_MAKE_VERSION(XR_VERSION_MAJOR(req.minApiVersionSupported), XR_VERSION_MINOR(req.minApiVersionSupported), 0))
    throw std::runtime_error("xr: the runtime needs Vulkan " + version(req.minApiVersionSupported) +
                             " or newer; ddish is written against " + version(ours));

  auto create_instance = xr.function<PFN_xrCreateVulkanInstanceKHR>("xrCreateVulkanInstanceKHR");
  auto graphics_device = xr.function<PFN_xrGetVulkanGraphicsDevice2KHR>("xrGetVulkanGraphicsDevice2KHR");
  auto create_device = xr.function<PFN_xrCreateVulkanDeviceKHR>("xrCreateVulkanDeviceKHR");
  const XrInstance instance = xr.handle();
  const XrSystemId system = xr.system();

  options.create_instance = [=](const VkInstanceCreateInfo& ci, VkInstance* out) {
    XrVulkanInstanceCreateInfoKHR info{XR_TYPE_VULKAN_INSTANCE_CREATE_INFO_KHR};
    info.systemId = system;
    info.pfnGetInstanceProcAddr = &vkGetInstanceProcAddr;
    info.vulkanCreateInfo = &ci;
    VkResult result = VK_ERROR_INITIALIZATION_FAILED;
    check(create_instance(instance, &info, out, &result), "xrCreateVulkanInstanceKHR");
    return result;
  };
  options.pick_physical = [=](VkInstance vk) {
    XrVulkanGraphicsDeviceGetInfoKHR info{XR_TYPE_VULKAN_GRAPHICS_DEVICE_GET_INFO_KHR};
    info.systemId = system;
    info.vulkanInstance = vk;
    VkPhysicalDevice device = VK_NULL_HANDLE;
    check(graphics_device(instance, &info, &device), "xrGetVulkanGraphicsDevice2KHR");
    return device;
  };
  options.create_device = [=](VkPhysicalDevice physical, const VkDeviceCreateInfo& ci, VkDevice* out) {
    XrVulkanDeviceCreateInfoKHR info{XR_TYPE_VULKAN_DEVICE_CREATE_INFO_KHR};
    info.systemId = system;
    info.pfnGetInstanceProcAddr = &vkGetInstanceProcAddr;
    info.vulkanPhysicalDevice = physical;
    info.vulkanCreateInfo = &ci;
    VkResult result = VK_ERROR_INITIALIZATION_FAILED;
    check(create_device(instance, &info, out, &result), "xrCreateVulkanDeviceKHR");
    return result;
  };
}

}  // namespace ddish::xr
