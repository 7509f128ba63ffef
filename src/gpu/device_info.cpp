#include "gpu/device_info.h"

#include <array>

#include "gpu/error.h"
#include "gpu/instance.h"

namespace ddish::gpu {

namespace {

constexpr std::uint32_t kVendorNvidia = 0x10DE;

DeviceType to_device_type(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return DeviceType::discrete;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return DeviceType::integrated;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return DeviceType::virtual_gpu;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return DeviceType::cpu;
    default: return DeviceType::other;
  }
}

DeviceInfo describe(std::uint32_t index, VkPhysicalDevice handle) {
  DeviceInfo info;
  info.index = index;
  info.handle = handle;

  VkPhysicalDeviceProperties basic{};
  vkGetPhysicalDeviceProperties(handle, &basic);
  // The extended property structs may only be chained when the device knows them: multiview
  // properties are core in 1.1, driver properties in 1.2.
  VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  VkPhysicalDeviceMultiviewProperties multiview{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MULTIVIEW_PROPERTIES};
  VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
  if (basic.apiVersion >= VK_API_VERSION_1_1) props.pNext = &multiview;
  if (basic.apiVersion >= VK_API_VERSION_1_2) multiview.pNext = &driver;
  vkGetPhysicalDeviceProperties2(handle, &props);

  info.name = props.properties.deviceName;
  info.type = to_device_type(props.properties.deviceType);
  info.api_version = props.properties.apiVersion;
  info.driver_version = props.properties.driverVersion;
  info.vendor_id = props.properties.vendorID;
  info.device_id = props.properties.deviceID;
  if (basic.apiVersion >= VK_API_VERSION_1_2) {
    info.driver_name = driver.driverName;
    info.driver_info = driver.driverInfo;
  }
  info.limits = props.properties.limits;
  info.timestamp_period = info.limits.timestampPeriod;
  info.max_multiview_view_count = multiview.maxMultiviewViewCount;
  info.color_sample_counts = info.limits.framebufferColorSampleCounts;
  info.depth_sample_counts = info.limits.framebufferDepthSampleCounts;

  if (basic.apiVersion >= VK_API_VERSION_1_2) {
    bool extensions = true;
    for (const std::string& name : ray_tracing_extensions())
      extensions = extensions && device_extension_available(handle, name);
    if (extensions) {
      VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
      VkPhysicalDeviceVulkan12Features v12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
      VkPhysicalDeviceAccelerationStructureFeaturesKHR as{
          VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR};
      VkPhysicalDeviceRayTracingPipelineFeaturesKHR rt{
          VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_TRACING_PIPELINE_FEATURES_KHR};
      features.pNext = &v12;
      v12.pNext = &as;
      as.pNext = &rt;
      vkGetPhysicalDeviceFeatures2(handle, &features);
      info.ray_tracing = v12.bufferDeviceAddress && as.accelerationStructure && rt.rayTracingPipeline;
    }
  }

  std::uint32_t family_count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(handle, &family_count, nullptr);
  std::vector<VkQueueFamilyProperties> families(family_count);
  vkGetPhysicalDeviceQueueFamilyProperties(handle, &family_count, families.data());
  constexpr VkQueueFlags wanted = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
  for (std::uint32_t i = 0; i < family_count; ++i) {
    if ((families[i].queueFlags & wanted) == wanted && families[i].queueCount > 0) {
      info.queue_family = i;
      info.timestamp_valid_bits = families[i].timestampValidBits;
      break;
    }
  }
  return info;
}

std::string device_list(const std::vector<DeviceInfo>& devices) {
  std::string list;
  for (const auto& device : devices) {
    if (!list.empty()) list += ", ";
    list += std::to_string(device.index) + ": " + device.name;
  }
  return list;
}

}  // namespace

bool device_extension_available(VkPhysicalDevice physical, const std::string& name) {
  std::uint32_t count = 0;
  if (vkEnumerateDeviceExtensionProperties(physical, nullptr, &count, nullptr) != VK_SUCCESS)
    return false;
  std::vector<VkExtensionProperties> extensions(count);
  if (vkEnumerateDeviceExtensionProperties(physical, nullptr, &count, extensions.data()) !=
      VK_SUCCESS)
    return false;
  for (const auto& e : extensions)
    if (name == e.extensionName) return true;
  return false;
}

const std::vector<std::string>& ray_tracing_extensions() {
  static const std::vector<std::string> names = {VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME,
                                                 VK_KHR_RAY_TRACING_PIPELINE_EXTENSION_NAME,
                                                 VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME};
  return names;
}

std::string DeviceInfo::unusable_reason() const {
  if (api_version < kRequiredApiVersion)
    return "Vulkan " + version_string(api_version) + " (ddish needs 1.3)";
  if (!queue_family) return "no queue family with both graphics and compute";
  return {};
}

std::vector<DeviceInfo> enumerate_devices(const Instance& instance) {
  std::uint32_t count = 0;
  check(vkEnumeratePhysicalDevices(instance.handle(), &count, nullptr),
        "vkEnumeratePhysicalDevices");
  std::vector<VkPhysicalDevice> handles(count);
  VkResult result = vkEnumeratePhysicalDevices(instance.handle(), &count, handles.data());
  if (result != VK_INCOMPLETE) check(result, "vkEnumeratePhysicalDevices");
  handles.resize(count);

  std::vector<DeviceInfo> devices;
  devices.reserve(count);
  for (std::uint32_t i = 0; i < count; ++i) devices.push_back(describe(i, handles[i]));
  return devices;
}

std::optional<std::uint32_t> default_device_index(const std::vector<DeviceInfo>& devices) {
  constexpr std::array preference = {DeviceType::discrete, DeviceType::integrated,
                                     DeviceType::virtual_gpu, DeviceType::cpu, DeviceType::other};
  for (DeviceType type : preference)
    for (const auto& device : devices)
      if (device.type == type && device.usable()) return device.index;
  return std::nullopt;
}

std::uint32_t select_device(const std::vector<DeviceInfo>& devices,
                            std::optional<std::uint32_t> requested) {
  if (devices.empty())
    throw GpuError("no Vulkan device found (install mesa-vulkan-drivers for the CPU device)");
  if (requested) {
    if (*requested >= devices.size())
      throw GpuError("Vulkan device " + std::to_string(*requested) + " does not exist: " +
                     std::to_string(devices.size()) + " device" +
                     (devices.size() == 1 ? "" : "s") + " found (" + device_list(devices) + ")");
    const DeviceInfo& device = devices[*requested];
    if (!device.usable())
      throw GpuError("Vulkan device " + std::to_string(*requested) + " (" + device.name +
                     ") cannot be used: " + device.unusable_reason());
    return *requested;
  }
  if (auto index = default_device_index(devices)) return *index;
  std::string reasons;
  for (const auto& device : devices)
    reasons += (reasons.empty() ? "" : "; ") + std::to_string(device.index) + ": " + device.name +
               ", " + device.unusable_reason();
  throw GpuError("no usable Vulkan device (" + reasons + ")");
}

std::string type_name(DeviceType type) {
  switch (type) {
    case DeviceType::discrete: return "discrete GPU";
    case DeviceType::integrated: return "integrated GPU";
    case DeviceType::virtual_gpu: return "virtual GPU";
    case DeviceType::cpu: return "CPU";
    case DeviceType::other: return "other";
  }
  return "other";
}

std::string version_string(std::uint32_t version) {
  return std::to_string(VK_API_VERSION_MAJOR(version)) + "." +
         std::to_string(VK_API_VERSION_MINOR(version)) + "." +
         std::to_string(VK_API_VERSION_PATCH(version));
}

std::string driver_version_string(const DeviceInfo& device) {
  const std::uint32_t v = device.driver_version;
  // NVIDIA packs 10.8.8.6 bits; Mesa and most others use the Vulkan version layout.
  if (device.vendor_id == kVendorNvidia)
    return std::to_string((v >> 22) & 0x3FF) + "." + std::to_string((v >> 14) & 0xFF) + "." +
           std::to_string((v >> 6) & 0xFF) + "." + std::to_string(v & 0x3F);
  return version_string(v);
}

std::vector<std::uint32_t> sample_counts(VkSampleCountFlags flags) {
  std::vector<std::uint32_t> counts;
  for (std::uint32_t bit = VK_SAMPLE_COUNT_1_BIT; bit <= VK_SAMPLE_COUNT_64_BIT; bit <<= 1)
    if ((flags & bit) != 0) counts.push_back(bit);  // the flag bits equal the sample counts
  return counts;
}

}  // namespace ddish::gpu
