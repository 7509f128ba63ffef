// The Vulkan instance: the loader and an optional validation layer. Headless by default: a
// surface extension is only there when a caller (the live window) lists it, and a caller that
// must create the instance itself (OpenXR's xrCreateVulkanInstanceKHR) gets the create info
// gpu/ built, so layers and extensions are chosen in one place.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "gpu/validation.h"

namespace ddish::gpu {

// The Vulkan version ddish is written against (dynamic rendering, synchronization2 in core).
inline constexpr std::uint32_t kRequiredApiVersion = VK_API_VERSION_1_3;

// The Khronos validation layer, installed by the vulkan-validationlayers package.
inline constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

struct InstanceOptions {
  // VK_LAYER_KHRONOS_validation plus a debug messenger. Also switched on by DDISH_VALIDATION=1.
  bool validation = false;
  // The layer's synchronization checks (missing barriers, hazards). Slower; only with validation.
  bool synchronization_validation = false;
  std::string application_name = "ddish";
  // Instance extensions beyond validation's (a window's surface extensions). A missing one
  // throws GpuError naming it.
  std::vector<std::string> extensions;
  // Set: called instead of vkCreateInstance with the create info built here (the OpenXR
  // binding creates the instance through its runtime). The instance is still destroyed here.
  std::function<VkResult(const VkInstanceCreateInfo&, VkInstance*)> create;
};

// True when the environment variable DDISH_VALIDATION is set to anything but "" or "0".
bool validation_requested_by_environment();

// Whether the loader can find VK_LAYER_KHRONOS_validation.
bool validation_layer_available();

class Instance {
 public:
  // Throws GpuError when there is no usable Vulkan loader (or it is older than 1.3), or when
  // validation is asked for and the layer is not installed.
  explicit Instance(const InstanceOptions& options = {});
  ~Instance();
  Instance(const Instance&) = delete;
  Instance& operator=(const Instance&) = delete;

  VkInstance handle() const { return instance_; }
  std::uint32_t loader_version() const { return loader_version_; }
  bool validation_enabled() const { return messenger_ != VK_NULL_HANDLE; }

  // Validation messages so far (always zero when validation is off).
  ValidationLog& validation() { return *log_; }
  const ValidationLog& validation() const { return *log_; }
  // The same log, shared: it outlives the instance, so what vkDestroyDevice and
  // vkDestroyInstance report (leaked objects) can still be read afterwards.
  std::shared_ptr<const ValidationLog> shared_validation() const { return log_; }

 private:
  // Created before the handles: callbacks during vkDestroyInstance still land in a live log.
  std::shared_ptr<ValidationLog> log_ = std::make_shared<ValidationLog>();
  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  std::uint32_t loader_version_ = 0;
};

}  // namespace ddish::gpu
