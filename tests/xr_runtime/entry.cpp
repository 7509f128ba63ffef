// The runtime's entry: loader negotiation, xrGetInstanceProcAddr, and the instance-level
// functions (instance, system, view configuration, events, strings).
#include <time.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>
#include <utility>

#include <openxr/openxr_reflection.h>

#include "functions.h"
#include "loader_interface.h"

namespace ddish::xr_runtime {

Runtime& runtime() {
  static Runtime r;
  return r;
}

XrTime now_ns() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<XrTime>(ts.tv_sec) * 1000000000 + ts.tv_nsec;
}

namespace {

constexpr const char* kRuntimeName = "ddish headless test runtime";

template <typename T>
void copy_name(char* dst, std::size_t size, const T& src) {
  std::snprintf(dst, size, "%s", src);
}

}  // namespace

XrResult XRAPI_CALL enumerate_instance_extensions(const char* layer, uint32_t capacity,
                                                  uint32_t* count, XrExtensionProperties* props) {
  if (layer != nullptr) return XR_ERROR_API_LAYER_NOT_PRESENT;
  if (count == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  *count = 1;
  if (capacity == 0) return XR_SUCCESS;
  if (props == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  if (props[0].type != XR_TYPE_EXTENSION_PROPERTIES) return XR_ERROR_VALIDATION_FAILURE;
  copy_name(props[0].extensionName, XR_MAX_EXTENSION_NAME_SIZE, XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME);
  props[0].extensionVersion = XR_KHR_vulkan_enable2_SPEC_VERSION;
  return XR_SUCCESS;
}

XrResult XRAPI_CALL create_instance(const XrInstanceCreateInfo* info, XrInstance* instance) {
  if (info == nullptr || instance == nullptr || info->type != XR_TYPE_INSTANCE_CREATE_INFO)
    return XR_ERROR_VALIDATION_FAILURE;
  const XrVersion v = info->applicationInfo.apiVersion;
  if (XR_VERSION_MAJOR(v) != 1 || XR_VERSION_MINOR(v) != 0) return XR_ERROR_API_VERSION_UNSUPPORTED;
  auto inst = std::make_unique<Instance>();
  for (uint32_t i = 0; i < info->enabledExtensionCount; ++i) {
    const char* name = info->enabledExtensionNames[i];
    if (std::strcmp(name, XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME) == 0)
      inst->vulkan_enable2 = true;
    else
      return XR_ERROR_EXTENSION_NOT_PRESENT;
  }
  try {
    if (const char* script = std::getenv("DDISH_XR_SCRIPT"); script && *script)
      inst->script = Script::load(script);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ddish test runtime: %s\n", e.what());
    return XR_ERROR_RUNTIME_FAILURE;
  }
  if (const char* out = std::getenv("DDISH_XR_OUT"); out && *out) inst->out = out;
  std::lock_guard lock(runtime().mutex);
  runtime().live[inst.get()] = Kind::instance;
  *instance = reinterpret_cast<XrInstance>(inst.release());
  return XR_SUCCESS;
}

XrResult XRAPI_CALL destroy_instance(XrInstance handle) {
  std::unique_lock lock(runtime().mutex);
  Instance* inst = runtime().get<Instance>(reinterpret_cast<std::uintptr_t>(handle), Kind::instance);
  if (inst == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (inst->session != nullptr) {  // children go with their parent
    XrSession s = reinterpret_cast<XrSession>(inst->session);
    lock.unlock();
    destroy_session(s);
    lock.lock();
  }
  runtime().live.erase(inst);
  delete inst;
  return XR_SUCCESS;
}

XrResult XRAPI_CALL get_instance_properties(XrInstance handle, XrInstanceProperties* props) {
  std::lock_guard lock(runtime().mutex);
  if (!runtime().get<Instance>(reinterpret_cast<std::uintptr_t>(handle), Kind::instance))
    return XR_ERROR_HANDLE_INVALID;
  if (props == nullptr || props->type != XR_TYPE_INSTANCE_PROPERTIES) return XR_ERROR_VALIDATION_FAILURE;
  props->runtimeVersion = XR_MAKE_VERSION(0, 1, 0);
  copy_name(props->runtimeName, XR_MAX_RUNTIME_NAME_SIZE, kRuntimeName);
  return XR_SUCCESS;
}

XrResult XRAPI_CALL poll_event(XrInstance handle, XrEventDataBuffer* event) {
  std::lock_guard lock(runtime().mutex);
  Instance* inst = runtime().get<Instance>(reinterpret_cast<std::uintptr_t>(handle), Kind::instance);
  if (inst == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (event == nullptr || event->type != XR_TYPE_EVENT_DATA_BUFFER) return XR_ERROR_VALIDATION_FAILURE;
  if (inst->events.empty()) return XR_EVENT_UNAVAILABLE;
  *event = inst->events.front();
  inst->events.pop_front();
  return XR_SUCCESS;
}

XrResult XRAPI_CALL result_to_string(XrInstance handle, XrResult value, char* buffer) {
  {
    std::lock_guard lock(runtime().mutex);
    if (!runtime().get<Instance>(reinterpret_cast<std::uintptr_t>(handle), Kind::instance))
      return XR_ERROR_HANDLE_INVALID;
  }
  if (buffer == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  const char* name = nullptr;
  switch (value) {
#define DDISH_XR_RESULT_NAME(n, v) \
  case n:                          \
    name = #n;                     \
    break;
    XR_LIST_ENUM_XrResult(DDISH_XR_RESULT_NAME)
#undef DDISH_XR_RESULT_NAME
    default:
      break;
  }
  if (name)
    copy_name(buffer, XR_MAX_RESULT_STRING_SIZE, name);
  else
    std::snprintf(buffer, XR_MAX_RESULT_STRING_SIZE, "XR_%s_%d", value < 0 ? "UNKNOWN_FAILURE" : "UNKNOWN_SUCCESS", int(value));
  return XR_SUCCESS;
}

XrResult XRAPI_CALL structure_type_to_string(XrInstance handle, XrStructureType value, char* buffer) {
  {
    std::lock_guard lock(runtime().mutex);
    if (!runtime().get<Instance>(reinterpret_cast<std::uintptr_t>(handle), Kind::instance))
      return XR_ERROR_HANDLE_INVALID;
  }
  if (buffer == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  const char* name = nullptr;
  switch (value) {
#define DDISH_XR_TYPE_NAME(n, v) \
  case n:                        \
    name = #n;                   \
    break;
    XR_LIST_ENUM_XrStructureType(DDISH_XR_TYPE_NAME)
#undef DDISH_XR_TYPE_NAME
    default:
      break;
  }
  if (name)
    copy_name(buffer, XR_MAX_STRUCTURE_NAME_SIZE, name);
  else
    std::snprintf(buffer, XR_MAX_STRUCTURE_NAME_SIZE, "XR_UNKNOWN_STRUCTURE_TYPE_%d", int(value));
  return XR_SUCCESS;
}

XrResult XRAPI_CALL get_system(XrInstance handle, const XrSystemGetInfo* info, XrSystemId* id) {
  std::lock_guard lock(runtime().mutex);
  if (!runtime().get<Instance>(reinterpret_cast<std::uintptr_t>(handle), Kind::instance))
    return XR_ERROR_HANDLE_INVALID;
  if (info == nullptr || id == nullptr || info->type != XR_TYPE_SYSTEM_GET_INFO)
    return XR_ERROR_VALIDATION_FAILURE;
  if (info->formFactor == XR_FORM_FACTOR_HANDHELD_DISPLAY) return XR_ERROR_FORM_FACTOR_UNSUPPORTED;
  if (info->formFactor != XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY) return XR_ERROR_VALIDATION_FAILURE;
  *id = kSystemId;
  return XR_SUCCESS;
}

XrResult XRAPI_CALL get_system_properties(XrInstance handle, XrSystemId id, XrSystemProperties* props) {
  std::lock_guard lock(runtime().mutex);
  if (!runtime().get<Instance>(reinterpret_cast<std::uintptr_t>(handle), Kind::instance))
    return XR_ERROR_HANDLE_INVALID;
  if (id != kSystemId) return XR_ERROR_SYSTEM_INVALID;
  if (props == nullptr || props->type != XR_TYPE_SYSTEM_PROPERTIES) return XR_ERROR_VALIDATION_FAILURE;
  props->systemId = kSystemId;
  props->vendorId = 0;
  copy_name(props->systemName, XR_MAX_SYSTEM_NAME_SIZE, "ddish scripted headset");
  props->graphicsProperties = {4096, 4096, 1};
  props->trackingProperties = {XR_TRUE, XR_TRUE};
  return XR_SUCCESS;
}

namespace {

// The checks every view-configuration query shares; the instance is looked up locked.
XrResult check_view_config(XrInstance handle, XrSystemId id, XrViewConfigurationType type,
                           Instance** out) {
  Instance* inst = runtime().get<Instance>(reinterpret_cast<std::uintptr_t>(handle), Kind::instance);
  if (inst == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (id != kSystemId) return XR_ERROR_SYSTEM_INVALID;
  if (type != XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO) return XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED;
  *out = inst;
  return XR_SUCCESS;
}

}  // namespace

XrResult XRAPI_CALL enumerate_view_configurations(XrInstance handle, XrSystemId id, uint32_t capacity,
                                                  uint32_t* count, XrViewConfigurationType* types) {
  std::lock_guard lock(runtime().mutex);
  if (!runtime().get<Instance>(reinterpret_cast<std::uintptr_t>(handle), Kind::instance))
    return XR_ERROR_HANDLE_INVALID;
  if (id != kSystemId) return XR_ERROR_SYSTEM_INVALID;
  return two_call(std::vector<XrViewConfigurationType>{XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO},
                  capacity, count, types);
}

XrResult XRAPI_CALL get_view_configuration_properties(XrInstance handle, XrSystemId id,
                                                      XrViewConfigurationType type,
                                                      XrViewConfigurationProperties* props) {
  std::lock_guard lock(runtime().mutex);
  Instance* inst = nullptr;
  if (XrResult r = check_view_config(handle, id, type, &inst); r != XR_SUCCESS) return r;
  if (props == nullptr || props->type != XR_TYPE_VIEW_CONFIGURATION_PROPERTIES)
    return XR_ERROR_VALIDATION_FAILURE;
  props->viewConfigurationType = type;
  props->fovMutable = XR_FALSE;
  return XR_SUCCESS;
}

XrResult XRAPI_CALL enumerate_view_configuration_views(XrInstance handle, XrSystemId id,
                                                       XrViewConfigurationType type, uint32_t capacity,
                                                       uint32_t* count, XrViewConfigurationView* views) {
  std::lock_guard lock(runtime().mutex);
  Instance* inst = nullptr;
  if (XrResult r = check_view_config(handle, id, type, &inst); r != XR_SUCCESS) return r;
  if (count == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  *count = 2;
  if (capacity == 0) return XR_SUCCESS;
  if (capacity < 2) return XR_ERROR_SIZE_INSUFFICIENT;
  if (views == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  for (int i = 0; i < 2; ++i) {
    if (views[i].type != XR_TYPE_VIEW_CONFIGURATION_VIEW) return XR_ERROR_VALIDATION_FAILURE;
    const auto w = static_cast<uint32_t>(inst->script.eye_width);
    const auto h = static_cast<uint32_t>(inst->script.eye_height);
    views[i].recommendedImageRectWidth = w;
    views[i].recommendedImageRectHeight = h;
    views[i].maxImageRectWidth = 4096;
    views[i].maxImageRectHeight = 4096;
    views[i].recommendedSwapchainSampleCount = 1;
    views[i].maxSwapchainSampleCount = 1;
  }
  return XR_SUCCESS;
}

XrResult XRAPI_CALL enumerate_blend_modes(XrInstance handle, XrSystemId id, XrViewConfigurationType type,
                                          uint32_t capacity, uint32_t* count, XrEnvironmentBlendMode* modes) {
  std::lock_guard lock(runtime().mutex);
  Instance* inst = nullptr;
  if (XrResult r = check_view_config(handle, id, type, &inst); r != XR_SUCCESS) return r;
  return two_call(std::vector<XrEnvironmentBlendMode>{XR_ENVIRONMENT_BLEND_MODE_OPAQUE}, capacity,
                  count, modes);
}

namespace {

using Fn = PFN_xrVoidFunction;
#define DDISH_XR_FN(f) reinterpret_cast<Fn>(&f)

XrResult XRAPI_CALL get_instance_proc_addr(XrInstance handle, const char* name, PFN_xrVoidFunction* function);

struct Entry {
  const char* name;
  Fn fn;
  bool needs_vulkan2;  // only with XR_KHR_vulkan_enable2 enabled
};

const Entry kEntries[] = {
    {"xrGetInstanceProcAddr", DDISH_XR_FN(get_instance_proc_addr), false},
    {"xrEnumerateInstanceExtensionProperties", DDISH_XR_FN(enumerate_instance_extensions), false},
    {"xrCreateInstance", DDISH_XR_FN(create_instance), false},
    {"xrDestroyInstance", DDISH_XR_FN(destroy_instance), false},
    {"xrGetInstanceProperties", DDISH_XR_FN(get_instance_properties), false},
    {"xrPollEvent", DDISH_XR_FN(poll_event), false},
    {"xrResultToString", DDISH_XR_FN(result_to_string), false},
    {"xrStructureTypeToString", DDISH_XR_FN(structure_type_to_string), false},
    {"xrGetSystem", DDISH_XR_FN(get_system), false},
    {"xrGetSystemProperties", DDISH_XR_FN(get_system_properties), false},
    {"xrEnumerateViewConfigurations", DDISH_XR_FN(enumerate_view_configurations), false},
    {"xrGetViewConfigurationProperties", DDISH_XR_FN(get_view_configuration_properties), false},
    {"xrEnumerateViewConfigurationViews", DDISH_XR_FN(enumerate_view_configuration_views), false},
    {"xrEnumerateEnvironmentBlendModes", DDISH_XR_FN(enumerate_blend_modes), false},
    {"xrCreateSession", DDISH_XR_FN(create_session), false},
    {"xrDestroySession", DDISH_XR_FN(destroy_session), false},
    {"xrBeginSession", DDISH_XR_FN(begin_session), false},
    {"xrEndSession", DDISH_XR_FN(end_session), false},
    {"xrRequestExitSession", DDISH_XR_FN(request_exit_session), false},
    {"xrEnumerateReferenceSpaces", DDISH_XR_FN(enumerate_reference_spaces), false},
    {"xrCreateReferenceSpace", DDISH_XR_FN(create_reference_space), false},
    {"xrDestroySpace", DDISH_XR_FN(destroy_space), false},
    {"xrWaitFrame", DDISH_XR_FN(wait_frame), false},
    {"xrBeginFrame", DDISH_XR_FN(begin_frame), false},
    {"xrEndFrame", DDISH_XR_FN(end_frame), false},
    {"xrLocateViews", DDISH_XR_FN(locate_views), false},
    {"xrEnumerateSwapchainFormats", DDISH_XR_FN(enumerate_swapchain_formats), false},
    {"xrCreateSwapchain", DDISH_XR_FN(create_swapchain), false},
    {"xrDestroySwapchain", DDISH_XR_FN(destroy_swapchain), false},
    {"xrEnumerateSwapchainImages", DDISH_XR_FN(enumerate_swapchain_images), false},
    {"xrAcquireSwapchainImage", DDISH_XR_FN(acquire_swapchain_image), false},
    {"xrWaitSwapchainImage", DDISH_XR_FN(wait_swapchain_image), false},
    {"xrReleaseSwapchainImage", DDISH_XR_FN(release_swapchain_image), false},
    {"xrGetVulkanGraphicsRequirements2KHR", DDISH_XR_FN(get_vulkan_requirements), true},
    {"xrCreateVulkanInstanceKHR", DDISH_XR_FN(create_vulkan_instance), true},
    {"xrCreateVulkanDeviceKHR", DDISH_XR_FN(create_vulkan_device), true},
    {"xrGetVulkanGraphicsDevice2KHR", DDISH_XR_FN(get_vulkan_device), true},
};

XrResult XRAPI_CALL get_instance_proc_addr(XrInstance handle, const char* name, PFN_xrVoidFunction* function) {
  if (name == nullptr || function == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  *function = nullptr;
  if (handle == XR_NULL_HANDLE) {
    // Before an instance exists only these may be asked for.
    for (const char* pre : {"xrEnumerateInstanceExtensionProperties", "xrCreateInstance", "xrGetInstanceProcAddr"})
      if (std::strcmp(name, pre) == 0)
        for (const Entry& e : kEntries)
          if (std::strcmp(e.name, name) == 0) {
            *function = e.fn;
            return XR_SUCCESS;
          }
    return XR_ERROR_HANDLE_INVALID;
  }
  std::lock_guard lock(runtime().mutex);
  Instance* inst = runtime().get<Instance>(reinterpret_cast<std::uintptr_t>(handle), Kind::instance);
  if (inst == nullptr) return XR_ERROR_HANDLE_INVALID;
  for (const Entry& e : kEntries) {
    if (std::strcmp(e.name, name) != 0) continue;
    if (e.needs_vulkan2 && !inst->vulkan_enable2) return XR_ERROR_FUNCTION_UNSUPPORTED;
    *function = e.fn;
    return XR_SUCCESS;
  }
  return XR_ERROR_FUNCTION_UNSUPPORTED;
}

}  // namespace

PFN_xrGetInstanceProcAddr instance_proc_addr() { return &get_instance_proc_addr; }

}  // namespace ddish::xr_runtime

// The one symbol the library exports (runtime.map): the loader's way in.
extern "C" __attribute__((visibility("default"))) XRAPI_ATTR XrResult XRAPI_CALL
xrNegotiateLoaderRuntimeInterface(
    const ddish::xr_runtime::NegotiateLoaderInfo* info,
    ddish::xr_runtime::NegotiateRuntimeRequest* request) {
  using namespace ddish::xr_runtime;
  if (info == nullptr || request == nullptr || info->structType != kStructLoaderInfo ||
      info->structVersion != kLoaderInfoStructVersion || info->structSize != sizeof(NegotiateLoaderInfo) ||
      request->structType != kStructRuntimeRequest ||
      request->structVersion != kRuntimeInfoStructVersion ||
      request->structSize != sizeof(NegotiateRuntimeRequest))
    return XR_ERROR_INITIALIZATION_FAILED;
  if (info->minInterfaceVersion > kLoaderRuntimeInterface || info->maxInterfaceVersion < kLoaderRuntimeInterface)
    return XR_ERROR_INITIALIZATION_FAILED;
  const XrVersion ours = XR_MAKE_VERSION(1, 0, 0);
  // This runtime speaks OpenXR 1.0.
  if (info->minApiVersion > XR_MAKE_VERSION(1, 0, 0xffffffffu) || info->maxApiVersion < ours)
    return XR_ERROR_INITIALIZATION_FAILED;
  request->runtimeInterfaceVersion = kLoaderRuntimeInterface;
  request->runtimeApiVersion = ours | XR_VERSION_PATCH(XR_CURRENT_API_VERSION);
  request->getInstanceProcAddr = instance_proc_addr();
  return XR_SUCCESS;
}
