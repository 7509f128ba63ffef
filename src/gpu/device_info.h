// What each Vulkan physical device is and can do, and which one ddish uses. Enumeration is kept
// apart from device creation so that `ddish devices` can list devices it would never open.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

namespace ddish::gpu {

class Instance;

// In the order of preference for the default device (see default_device_index).
enum class DeviceType { discrete, integrated, virtual_gpu, cpu, other };

struct DeviceInfo {
  std::uint32_t index = 0;  // position in vkEnumeratePhysicalDevices, what --device takes
  VkPhysicalDevice handle = VK_NULL_HANDLE;
  std::string name;
  DeviceType type = DeviceType::other;
  std::uint32_t api_version = 0;
  std::uint32_t driver_version = 0;  // vendor-encoded: use driver_version_string()
  std::uint32_t vendor_id = 0;
  std::uint32_t device_id = 0;
  std::string driver_name;  // e.g. "llvmpipe"; empty before Vulkan 1.2
  std::string driver_info;  // e.g. "Mesa 22.3.6 (LLVM 15.0.6)"

  // A queue family with graphics and compute (every such family also does transfers).
  std::optional<std::uint32_t> queue_family;
  std::uint32_t timestamp_valid_bits = 0;  // of that family; 0: no timestamps there
  float timestamp_period = 0.0f;           // nanoseconds per timestamp tick

  std::uint32_t max_multiview_view_count = 0;
  VkSampleCountFlags color_sample_counts = 0;  // framebuffer colour MSAA counts
  VkSampleCountFlags depth_sample_counts = 0;  // framebuffer depth MSAA counts
  VkPhysicalDeviceLimits limits{};
  // Vulkan ray-tracing pipelines are there: VK_KHR_ray_tracing_pipeline,
  // VK_KHR_acceleration_structure and VK_KHR_deferred_host_operations with their features and
  // bufferDeviceAddress (Mesa 25 lavapipe has them; Mesa 22 does not). What trace_vk/ needs.
  bool ray_tracing = false;

  // Vulkan 1.3 and a graphics+compute queue: what ddish needs to run on a device.
  bool usable() const { return unusable_reason().empty(); }
  std::string unusable_reason() const;  // empty when usable
  bool timestamps_supported() const { return queue_family && timestamp_valid_bits > 0; }
  // MSAA counts that both colour and depth attachments support (what the rasterizer can use).
  VkSampleCountFlags msaa_sample_counts() const { return color_sample_counts & depth_sample_counts; }
};

// Whether the physical device offers the device extension `name`.
bool device_extension_available(VkPhysicalDevice physical, const std::string& name);

// The device extensions ray tracing needs (DeviceInfo::ray_tracing).
const std::vector<std::string>& ray_tracing_extensions();

// Every physical device the loader reports, in its order.
std::vector<DeviceInfo> enumerate_devices(const Instance& instance);

// The first usable discrete GPU, else integrated, else virtual, else CPU (lavapipe), else other;
// nullopt when no device is usable.
std::optional<std::uint32_t> default_device_index(const std::vector<DeviceInfo>& devices);

// The device to open: `requested` when given (it must exist and be usable), else the default.
// Throws GpuError with one line naming the problem and the devices there are.
std::uint32_t select_device(const std::vector<DeviceInfo>& devices,
                            std::optional<std::uint32_t> requested);

std::string type_name(DeviceType type);                // "discrete GPU", "CPU", ...
std::string version_string(std::uint32_t version);     // VK_MAKE_API_VERSION -> "1.3.230"
std::string driver_version_string(const DeviceInfo& device);  // decoded per vendor
std::vector<std::uint32_t> sample_counts(VkSampleCountFlags flags);  // {1, 4, ...}

}  // namespace ddish::gpu
