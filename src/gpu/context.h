// An instance and a device together, in the order they must be destroyed: what a renderer or a
// command needs to start using Vulkan in one line.
//
//   gpu::Context gpu({.validation = opts.validation, .device_index = opts.device});
//   gpu::Buffer b(gpu.device(), bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUse::upload);
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "gpu/device.h"
#include "gpu/instance.h"

namespace ddish::gpu {

struct ContextOptions {
  bool validation = false;                     // or DDISH_VALIDATION=1
  bool synchronization_validation = false;     // only with validation
  std::optional<std::uint32_t> device_index;   // --device N
  std::string application_name = "ddish";
  // The window's surface extensions and VK_KHR_swapchain (gpu/instance.h, gpu/device.h).
  std::vector<std::string> instance_extensions;
  std::vector<std::string> device_extensions;
  bool ray_tracing = false;  // DeviceOptions::ray_tracing
  // OpenXR's binding: the runtime creates both handles from the create infos built here, and
  // names the physical device once the instance exists (it overrides device_index).
  std::function<VkResult(const VkInstanceCreateInfo&, VkInstance*)> create_instance;
  std::function<VkPhysicalDevice(VkInstance)> pick_physical;
  std::function<VkResult(VkPhysicalDevice, const VkDeviceCreateInfo&, VkDevice*)> create_device;
};

class Context {
 public:
  explicit Context(const ContextOptions& options = {})
      : instance_({.validation = options.validation,
                   .synchronization_validation = options.synchronization_validation,
                   .application_name = options.application_name,
                   .extensions = options.instance_extensions,
                   .create = options.create_instance}),
        device_(instance_,
                {.index = options.device_index,
                 .physical = options.pick_physical ? options.pick_physical(instance_.handle())
                                                   : VK_NULL_HANDLE,
                 .extensions = options.device_extensions,
                 .ray_tracing = options.ray_tracing,
                 .create = options.create_device}) {}

  Instance& instance() { return instance_; }
  const Instance& instance() const { return instance_; }
  Device& device() { return device_; }
  const Device& device() const { return device_; }
  const ValidationLog& validation() const { return instance_.validation(); }

 private:
  Instance instance_;  // constructed first, destroyed last
  Device device_;
};

}  // namespace ddish::gpu
