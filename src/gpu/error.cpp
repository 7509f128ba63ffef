#include "gpu/error.h"

namespace ddish::gpu {

std::string result_name(VkResult result) {
  switch (result) {
#define DDISH_VK_RESULT(name) \
  case name:                  \
    return #name;
    DDISH_VK_RESULT(VK_SUCCESS)
    DDISH_VK_RESULT(VK_NOT_READY)
    DDISH_VK_RESULT(VK_TIMEOUT)
    DDISH_VK_RESULT(VK_EVENT_SET)
    DDISH_VK_RESULT(VK_EVENT_RESET)
    DDISH_VK_RESULT(VK_INCOMPLETE)
    DDISH_VK_RESULT(VK_ERROR_OUT_OF_HOST_MEMORY)
    DDISH_VK_RESULT(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    DDISH_VK_RESULT(VK_ERROR_INITIALIZATION_FAILED)
    DDISH_VK_RESULT(VK_ERROR_DEVICE_LOST)
    DDISH_VK_RESULT(VK_ERROR_MEMORY_MAP_FAILED)
    DDISH_VK_RESULT(VK_ERROR_LAYER_NOT_PRESENT)
    DDISH_VK_RESULT(VK_ERROR_EXTENSION_NOT_PRESENT)
    DDISH_VK_RESULT(VK_ERROR_FEATURE_NOT_PRESENT)
    DDISH_VK_RESULT(VK_ERROR_INCOMPATIBLE_DRIVER)
    DDISH_VK_RESULT(VK_ERROR_TOO_MANY_OBJECTS)
    DDISH_VK_RESULT(VK_ERROR_FORMAT_NOT_SUPPORTED)
    DDISH_VK_RESULT(VK_ERROR_FRAGMENTED_POOL)
    DDISH_VK_RESULT(VK_ERROR_UNKNOWN)
    DDISH_VK_RESULT(VK_ERROR_OUT_OF_POOL_MEMORY)
    DDISH_VK_RESULT(VK_ERROR_INVALID_EXTERNAL_HANDLE)
    DDISH_VK_RESULT(VK_ERROR_FRAGMENTATION)
    DDISH_VK_RESULT(VK_ERROR_INVALID_OPAQUE_CAPTURE_ADDRESS)
    DDISH_VK_RESULT(VK_PIPELINE_COMPILE_REQUIRED)
    DDISH_VK_RESULT(VK_ERROR_VALIDATION_FAILED_EXT)
#undef DDISH_VK_RESULT
    default:
      return "VkResult " + std::to_string(static_cast<int>(result));
  }
}

void check(VkResult result, std::string_view what) {
  if (result == VK_SUCCESS) return;
  std::string message = std::string(what) + " failed: " + result_name(result);
  // The results a user can act on get what to do: the call alone does not say it.
  switch (result) {
    case VK_ERROR_OUT_OF_DEVICE_MEMORY:
    case VK_ERROR_OUT_OF_HOST_MEMORY:
      message += " (out of memory: fewer or smaller views, a lower --msaa or --view-batch)";
      break;
    case VK_ERROR_DEVICE_LOST:
      message += " (the GPU was reset or its driver failed; nothing more can run on this device)";
      break;
    default: break;
  }
  throw GpuError(message);
}

}  // namespace ddish::gpu
