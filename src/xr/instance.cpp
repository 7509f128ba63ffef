#include "xr/instance.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>
#include <openxr/openxr_platform.h>

#include "xr/error.h"

namespace ddish::xr {

namespace {

bool has_layer(const char* name) {
  std::uint32_t n = 0;
  if (XR_FAILED(xrEnumerateApiLayerProperties(0, &n, nullptr))) return false;
  std::vector<XrApiLayerProperties> layers(n, {XR_TYPE_API_LAYER_PROPERTIES});
  if (XR_FAILED(xrEnumerateApiLayerProperties(n, &n, layers.data()))) return false;
  return std::any_of(layers.begin(), layers.end(),
                     [&](const XrApiLayerProperties& l) { return std::strcmp(l.layerName, name) == 0; });
}

// The extensions the runtime (layer == nullptr) or a layer offers; empty when the loader
// cannot ask (no runtime: xrCreateInstance then says why).
std::vector<std::string> extensions(const char* layer) {
  std::uint32_t n = 0;
  if (XR_FAILED(xrEnumerateInstanceExtensionProperties(layer, 0, &n, nullptr))) return {};
  std::vector<XrExtensionProperties> props(n, {XR_TYPE_EXTENSION_PROPERTIES});
  if (XR_FAILED(xrEnumerateInstanceExtensionProperties(layer, n, &n, props.data()))) return {};
  std::vector<std::string> names;
  for (const auto& p : props) names.emplace_back(p.extensionName);
  return names;
}

bool contains(const std::vector<std::string>& v, const char* s) {
  return std::find(v.begin(), v.end(), s) != v.end();
}

std::string no_runtime_message(XrResult result) {
  const char* json = std::getenv("XR_RUNTIME_JSON");
  const std::string where =
      json && *json ? std::string("XR_RUNTIME_JSON=") + json + " names no loadable runtime"
                    : std::string("no OpenXR runtime is installed: set XR_RUNTIME_JSON to a runtime manifest");
  return "xr: " + where + " (" + result_name(result) +
         "), or make one the active runtime (active_runtime.json in $XDG_CONFIG_HOME/openxr/1/ or "
         "/etc/xdg/openxr/1/: Monado, SteamVR)";
}

}  // namespace

Instance::Instance(const InstanceOptions& options) {
  // The loader logs every failure to stderr in several lines; ddish says what failed in one
  // (NoRuntime). XR_LOADER_DEBUG set by the user (error, warn, info, verbose) still wins.
  ::setenv("XR_LOADER_DEBUG", "none", 0);
  std::vector<const char*> layers;
  if (options.validation) {
    if (!has_layer(kCoreValidationLayer))
      throw std::runtime_error(std::string("xr: validation asked for but the OpenXR layer ") + kCoreValidationLayer +
                               " is not installed (Debian openxr-layer-corevalidation)");
    layers.push_back(kCoreValidationLayer);
  }
  std::vector<std::string> offered = extensions(nullptr);
  if (options.validation)
    for (std::string& e : extensions(kCoreValidationLayer)) offered.push_back(std::move(e));
  std::vector<const char*> enabled{XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME};
  const bool debug_utils = options.validation && contains(offered, XR_EXT_DEBUG_UTILS_EXTENSION_NAME);
  if (debug_utils) enabled.push_back(XR_EXT_DEBUG_UTILS_EXTENSION_NAME);
  if (!offered.empty() && !contains(offered, XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME))
    throw std::runtime_error("xr: the OpenXR runtime has no XR_KHR_vulkan_enable2 (ddish renders with Vulkan)");

  XrInstanceCreateInfo ci{XR_TYPE_INSTANCE_CREATE_INFO};
  std::snprintf(ci.applicationInfo.applicationName, XR_MAX_APPLICATION_NAME_SIZE, "%s", options.application_name.c_str());
  ci.applicationInfo.applicationVersion = 1;
  std::snprintf(ci.applicationInfo.engineName, XR_MAX_ENGINE_NAME_SIZE, "ddish");
  ci.applicationInfo.engineVersion = 1;
  ci.applicationInfo.apiVersion = XR_MAKE_VERSION(1, 0, XR_VERSION_PATCH(XR_CURRENT_API_VERSION));
  ci.enabledApiLayerCount = static_cast<std::uint32_t>(layers.size());
  ci.enabledApiLayerNames = layers.data();
  ci.enabledExtensionCount = static_cast<std::uint32_t>(enabled.size());
  ci.enabledExtensionNames = enabled.data();
  // Chained, the messenger also hears xrCreateInstance / xrDestroyInstance themselves.
  XrDebugUtilsMessengerCreateInfoEXT mi{XR_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  mi.messageSeverities = XR_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | XR_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  mi.messageTypes = XR_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | XR_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                    XR_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT | XR_DEBUG_UTILS_MESSAGE_TYPE_CONFORMANCE_BIT_EXT;
  mi.userCallback = &Instance::message;
  mi.userData = this;
  if (debug_utils) ci.next = &mi;
  const XrResult r = xrCreateInstance(&ci, &instance_);
  if (r == XR_ERROR_RUNTIME_UNAVAILABLE || r == XR_ERROR_RUNTIME_FAILURE || r == XR_ERROR_INSTANCE_LOST ||
      r == XR_ERROR_INITIALIZATION_FAILED || r == XR_ERROR_FILE_ACCESS_ERROR || r == XR_ERROR_FILE_CONTENTS_INVALID)
    throw NoRuntime(no_runtime_message(r));
  check(r, "xrCreateInstance");
  try {
    if (debug_utils) {
      auto create = function<PFN_xrCreateDebugUtilsMessengerEXT>("xrCreateDebugUtilsMessengerEXT");
      check(create(instance_, &mi, &messenger_), "xrCreateDebugUtilsMessengerEXT");
    }
    XrInstanceProperties ip{XR_TYPE_INSTANCE_PROPERTIES};
    check(xrGetInstanceProperties(instance_, &ip), "xrGetInstanceProperties");
    runtime_name_ = ip.runtimeName;
    XrSystemGetInfo si{XR_TYPE_SYSTEM_GET_INFO};
    si.formFactor = XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY;
    const XrResult sr = xrGetSystem(instance_, &si, &system_);
    if (sr == XR_ERROR_FORM_FACTOR_UNAVAILABLE)
      throw std::runtime_error("xr: the headset is not connected (" + runtime_name_ + ": XR_ERROR_FORM_FACTOR_UNAVAILABLE)");
    check(sr, "xrGetSystem(HEAD_MOUNTED_DISPLAY)");
    XrSystemProperties sp{XR_TYPE_SYSTEM_PROPERTIES};
    check(xrGetSystemProperties(instance_, system_, &sp), "xrGetSystemProperties");
    system_name_ = sp.systemName;
    std::uint32_t n = 0;
    check(xrEnumerateViewConfigurations(instance_, system_, 0, &n, nullptr), "xrEnumerateViewConfigurations");
    std::vector<XrViewConfigurationType> configs(n);
    check(xrEnumerateViewConfigurations(instance_, system_, n, &n, configs.data()), "xrEnumerateViewConfigurations");
    if (std::find(configs.begin(), configs.end(), XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO) == configs.end())
      throw std::runtime_error("xr: " + system_name_ + " has no PRIMARY_STEREO view configuration");
    check(xrEnumerateViewConfigurationViews(instance_, system_, XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO, 0, &n, nullptr),
          "xrEnumerateViewConfigurationViews");
    if (n != 2) throw std::runtime_error("xr: PRIMARY_STEREO has " + std::to_string(n) + " views, not 2");
    std::vector<XrViewConfigurationView> views(n, {XR_TYPE_VIEW_CONFIGURATION_VIEW});
    check(xrEnumerateViewConfigurationViews(instance_, system_, XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO, n, &n, views.data()),
          "xrEnumerateViewConfigurationViews");
    for (int e = 0; e < 2; ++e)
      recommended_[e] = {views[e].recommendedImageRectWidth, views[e].recommendedImageRectHeight};
    check(xrEnumerateEnvironmentBlendModes(instance_, system_, XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO, 0, &n, nullptr),
          "xrEnumerateEnvironmentBlendModes");
    std::vector<XrEnvironmentBlendMode> modes(n);
    check(xrEnumerateEnvironmentBlendModes(instance_, system_, XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO, n, &n, modes.data()),
          "xrEnumerateEnvironmentBlendModes");
    if (std::find(modes.begin(), modes.end(), XR_ENVIRONMENT_BLEND_MODE_OPAQUE) == modes.end())
      throw std::runtime_error("xr: " + system_name_ + " has no opaque blend mode");
  } catch (...) {
    release();
    throw;
  }
}

Instance::~Instance() { release(); }

void Instance::release() {
  if (messenger_ != XR_NULL_HANDLE) {
    auto destroy = reinterpret_cast<PFN_xrDestroyDebugUtilsMessengerEXT>(void_function("xrDestroyDebugUtilsMessengerEXT"));
    destroy(messenger_);
    messenger_ = XR_NULL_HANDLE;
  }
  if (instance_ != XR_NULL_HANDLE) xrDestroyInstance(instance_);
  instance_ = XR_NULL_HANDLE;
}

PFN_xrVoidFunction Instance::void_function(const char* name) const {
  PFN_xrVoidFunction f = nullptr;
  check(xrGetInstanceProcAddr(instance_, name, &f), name);
  return f;
}

XrBool32 XRAPI_CALL Instance::message(XrDebugUtilsMessageSeverityFlagsEXT severity, XrDebugUtilsMessageTypeFlagsEXT,
                                      const XrDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  auto* self = static_cast<Instance*>(user);
  self->messages_.fetch_add(1);
  std::fprintf(stderr, "xr: OpenXR %s: %s%s%s\n",
               (severity & XR_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) ? "validation error" : "warning",
               data && data->functionName ? data->functionName : "", data && data->functionName ? ": " : "",
               data && data->message ? data->message : "");
  return XR_FALSE;
}

}  // namespace ddish::xr
