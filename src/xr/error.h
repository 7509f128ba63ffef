// OpenXR failures as exceptions with one-line messages: XrError carries the result; NoRuntime is
// what a machine without an OpenXR runtime gets, naming where the loader looks for one.
#pragma once

#include <stdexcept>
#include <string>

#include <openxr/openxr.h>

namespace ddish::xr {

class XrError : public std::runtime_error {
 public:
  XrError(const std::string& what, XrResult result);
  XrResult result() const { return result_; }

 private:
  XrResult result_;
};

class NoRuntime : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// "XR_ERROR_SESSION_LOST" for a known result, else its number.
std::string result_name(XrResult result);

// Throws XrError "WHAT failed: RESULT_NAME" unless XR_SUCCEEDED(result); returns the result
// (a success code such as XR_SESSION_LOSS_PENDING is the caller's to read).
XrResult check(XrResult result, const char* what);

}  // namespace ddish::xr
