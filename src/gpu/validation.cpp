#include "gpu/validation.h"

#include <cstdio>

namespace ddish::gpu {

namespace {
constexpr std::size_t kKeptMessages = 64;
}

std::vector<std::string> ValidationLog::error_messages() const {
  std::lock_guard lock(mutex_);
  return error_messages_;
}

VkDebugUtilsMessengerCreateInfoEXT ValidationLog::messenger_info() {
  VkDebugUtilsMessengerCreateInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                         VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                     VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                     VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  info.pfnUserCallback = &ValidationLog::callback;
  info.pUserData = this;
  return info;
}

VKAPI_ATTR VkBool32 VKAPI_CALL ValidationLog::callback(
    VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT types,
    const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  if (data != nullptr && user != nullptr)
    static_cast<ValidationLog*>(user)->record(severity, types, *data);
  // VK_FALSE: the call that triggered the message goes ahead, as the spec asks of applications.
  return VK_FALSE;
}

void ValidationLog::record(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                           VkDebugUtilsMessageTypeFlagsEXT types,
                           const VkDebugUtilsMessengerCallbackDataEXT& data) {
  // Only the validation layer's errors mean the program used Vulkan wrongly; a loader that cannot
  // read some unrelated driver's manifest also says "error", but that is the machine, not us.
  const bool is_error = (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) != 0 &&
                        (types & VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT) != 0;
  std::string text = data.pMessage != nullptr ? data.pMessage : "(no message)";
  if (data.pMessageIdName != nullptr && text.find(data.pMessageIdName) == std::string::npos)
    text = std::string(data.pMessageIdName) + ": " + text;

  if (is_error) {
    errors_.fetch_add(1);
    std::lock_guard lock(mutex_);
    if (error_messages_.size() < kKeptMessages) error_messages_.push_back(text);
  } else {
    warnings_.fetch_add(1);
  }
  if (echo_.load())
    std::fprintf(stderr, "[vulkan %s] %s\n", is_error ? "error" : "warning", text.c_str());
}

}  // namespace ddish::gpu
