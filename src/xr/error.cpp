#include "xr/error.h"

#include <openxr/openxr_reflection.h>

namespace ddish::xr {

XrError::XrError(const std::string& what, XrResult result) : std::runtime_error(what), result_(result) {}

std::string result_name(XrResult result) {
  switch (result) {
#define DDISH_XR_NAME(name, value) \
  case name:                       \
    return #name;
    XR_LIST_ENUM_XrResult(DDISH_XR_NAME)
#undef DDISH_XR_NAME
    default:
      return "XrResult " + std::to_string(static_cast<int>(result));
  }
}

XrResult check(XrResult result, const char* what) {
  if (XR_FAILED(result)) throw XrError(std::string(what) + " failed: " + result_name(result), result);
  return result;
}

}  // namespace ddish::xr
