// The OpenXR instance through the system loader (libopenxr_loader), with XR_KHR_vulkan_enable2,
// and its head-mounted system in the PRIMARY_STEREO view configuration. With validation on
// (DDISH_VALIDATION=1, as for Vulkan) the Khronos core validation layer
// (XR_APILAYER_LUNARG_core_validation, Debian openxr-layer-corevalidation) is enabled and its
// messages arrive through an XR_EXT_debug_utils messenger: counted, and echoed to stderr.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <string>

#include <openxr/openxr.h>

namespace ddish::xr {

inline constexpr const char* kCoreValidationLayer = "XR_APILAYER_LUNARG_core_validation";

struct InstanceOptions {
  std::string application_name = "ddish";
  bool validation = false;  // the core validation layer (an error when it is not installed)
};

struct EyeSize {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
};

class Instance {
 public:
  // Throws NoRuntime (one line naming XR_RUNTIME_JSON and active_runtime.json) when the loader
  // finds no runtime or cannot load it, XrError for any other failure, and std::runtime_error
  // when the system has no PRIMARY_STEREO configuration or no opaque blend mode.
  explicit Instance(const InstanceOptions& options = {});
  ~Instance();
  Instance(const Instance&) = delete;
  Instance& operator=(const Instance&) = delete;

  XrInstance handle() const { return instance_; }
  XrSystemId system() const { return system_; }
  const std::string& runtime_name() const { return runtime_name_; }
  const std::string& system_name() const { return system_name_; }
  // The runtime's recommended image size of each eye.
  const std::array<EyeSize, 2>& recommended() const { return recommended_; }

  bool validation_enabled() const { return messenger_ != XR_NULL_HANDLE; }
  // Warnings and errors the core validation layer (or the loader) reported so far.
  std::uint32_t validation_messages() const { return messages_.load(); }

  // An instance function by name; throws XrError when the runtime lacks it.
  template <typename F>
  F function(const char* name) const {
    return reinterpret_cast<F>(void_function(name));
  }

 private:
  PFN_xrVoidFunction void_function(const char* name) const;
  void release();
  static XrBool32 XRAPI_CALL message(XrDebugUtilsMessageSeverityFlagsEXT severity,
                                     XrDebugUtilsMessageTypeFlagsEXT types,
                                     const XrDebugUtilsMessengerCallbackDataEXT* data, void* user);

  XrInstance instance_ = XR_NULL_HANDLE;
  XrDebugUtilsMessengerEXT messenger_ = XR_NULL_HANDLE;
  XrSystemId system_ = XR_NULL_SYSTEM_ID;
  std::string runtime_name_;
  std::string system_name_;
  std::array<EyeSize, 2> recommended_{};
  std::atomic<std::uint32_t> messages_{0};
};

}  // namespace ddish::xr
