// XR_KHR_vulkan_enable2: the runtime creates the app's Vulkan instance and device with the
// app's own create infos (a headless runtime needs no extra extensions) and names the physical
// device: the first discrete or integrated GPU, else the first device (lavapipe here), the
// same rule as gpu::default_device_index.
#include <vector>

#include "functions.h"

namespace ddish::xr_runtime {

namespace {

Instance* instance_of(XrInstance handle) {
  return runtime().get<Instance>(reinterpret_cast<std::uintptr_t>(handle), Kind::instance);
}

}  // namespace

XrResult XRAPI_CALL get_vulkan_requirements(XrInstance handle, XrSystemId id,
                                            XrGraphicsRequirementsVulkanKHR* req) {
  std::lock_guard lock(runtime().mutex);
  Instance* inst = instance_of(handle);
  if (inst == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (id != kSystemId) return XR_ERROR_SYSTEM_INVALID;
  if (req == nullptr || req->type != XR_TYPE_GRAPHICS_REQUIREMENTS_VULKAN2_KHR)
    return XR_ERROR_VALIDATION_FAILURE;
  req->minApiVersionSupported = XR_MAKE_VERSION(1, 1, 0);
  req->maxApiVersionSupported = XR_MAKE_VERSION(1, 3, 0);
  inst->requirements_queried = true;
  return XR_SUCCESS;
}

XrResult XRAPI_CALL create_vulkan_instance(XrInstance handle, const XrVulkanInstanceCreateInfoKHR* info,
                                           VkInstance* vk_instance, VkResult* vk_result) {
  {
    std::lock_guard lock(runtime().mutex);
    Instance* inst = instance_of(handle);
    if (inst == nullptr) return XR_ERROR_HANDLE_INVALID;
    if (info == nullptr || vk_instance == nullptr || vk_result == nullptr ||
        info->type != XR_TYPE_VULKAN_INSTANCE_CREATE_INFO_KHR || info->pfnGetInstanceProcAddr == nullptr ||
        info->vulkanCreateInfo == nullptr)
      return XR_ERROR_VALIDATION_FAILURE;
    if (info->systemId != kSystemId) return XR_ERROR_SYSTEM_INVALID;
  }
  auto create = reinterpret_cast<PFN_vkCreateInstance>(info->pfnGetInstanceProcAddr(VK_NULL_HANDLE, "vkCreateInstance"));
  if (create == nullptr) return XR_ERROR_RUNTIME_FAILURE;
  *vk_result = create(info->vulkanCreateInfo, info->vulkanAllocator, vk_instance);
  return XR_SUCCESS;
}

XrResult XRAPI_CALL get_vulkan_device(XrInstance handle, const XrVulkanGraphicsDeviceGetInfoKHR* info,
                                      VkPhysicalDevice* device) {
  std::lock_guard lock(runtime().mutex);
  Instance* inst = instance_of(handle);
  if (inst == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (info == nullptr || device == nullptr || info->type != XR_TYPE_VULKAN_GRAPHICS_DEVICE_GET_INFO_KHR ||
      info->vulkanInstance == VK_NULL_HANDLE)
    return XR_ERROR_VALIDATION_FAILURE;
  if (info->systemId != kSystemId) return XR_ERROR_SYSTEM_INVALID;
  uint32_t n = 0;
  if (vkEnumeratePhysicalDevices(info->vulkanInstance, &n, nullptr) != VK_SUCCESS || n == 0)
    return XR_ERROR_RUNTIME_FAILURE;
  std::vector<VkPhysicalDevice> devices(n);
  vkEnumeratePhysicalDevices(info->vulkanInstance, &n, devices.data());
  VkPhysicalDevice chosen = devices[0];
  for (VkPhysicalDevice d : devices) {
    VkPhysicalDeviceProperties p{};
    vkGetPhysicalDeviceProperties(d, &p);
    if (p.deviceType == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU || p.deviceType == VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU) {
      chosen = d;
      break;
    }
  }
  inst->named_device = chosen;
  *device = chosen;
  return XR_SUCCESS;
}

XrResult XRAPI_CALL create_vulkan_device(XrInstance handle, const XrVulkanDeviceCreateInfoKHR* info,
                                         VkDevice* vk_device, VkResult* vk_result) {
  {
    std::lock_guard lock(runtime().mutex);
    Instance* inst = instance_of(handle);
    if (inst == nullptr) return XR_ERROR_HANDLE_INVALID;
    if (info == nullptr || vk_device == nullptr || vk_result == nullptr ||
        info->type != XR_TYPE_VULKAN_DEVICE_CREATE_INFO_KHR || info->pfnGetInstanceProcAddr == nullptr ||
        info->vulkanCreateInfo == nullptr || info->vulkanPhysicalDevice == VK_NULL_HANDLE)
      return XR_ERROR_VALIDATION_FAILURE;
    if (info->systemId != kSystemId) return XR_ERROR_SYSTEM_INVALID;
    // The device must be on the physical device this runtime named.
    if (info->vulkanPhysicalDevice != inst->named_device) return XR_ERROR_VALIDATION_FAILURE;
  }
  // vkCreateDevice is a device-level entry reached through the instance of the physical device;
  // the loader's global vkCreateDevice trampoline dispatches on it.
  *vk_result = vkCreateDevice(info->vulkanPhysicalDevice, info->vulkanCreateInfo, info->vulkanAllocator, vk_device);
  return XR_SUCCESS;
}

}  // namespace ddish::xr_runtime
