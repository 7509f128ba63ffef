// Errors of the gpu module. Everything that can go wrong with Vulkan (no device, a device index
// out of range, a missing SPIR-V file, a failed call) is thrown as a GpuError whose message is one
// line a user can act on; the command line prints it as is.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

#include <vulkan/vulkan.h>

namespace ddish::gpu {

class GpuError : public std::runtime_error {
 public:
  explicit GpuError(const std::string& message) : std::runtime_error(message) {}
};

// The enumerator's name ("VK_ERROR_OUT_OF_DEVICE_MEMORY"), or the number for unknown codes.
std::string result_name(VkResult result);

// Throws GpuError("<what> failed: <VkResult name>") unless result is VK_SUCCESS. Calls that can
// return other success codes (VK_INCOMPLETE, VK_TIMEOUT, VK_NOT_READY) are checked by hand.
void check(VkResult result, std::string_view what);

}  // namespace ddish::gpu
