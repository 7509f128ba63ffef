// What the Khronos validation layer reports, counted. The layer talks through a
// VK_EXT_debug_utils messenger whose callback lands here; each message is echoed to stderr and
// kept, so that a test can fail when a validation error appeared during it and say which one.
#pragma once

#include <atomic>
#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

namespace ddish::gpu {

class ValidationLog {
 public:
  ValidationLog() = default;
  ValidationLog(const ValidationLog&) = delete;
  ValidationLog& operator=(const ValidationLog&) = delete;

  // Counts since the instance was created. Errors are what the validation layer flags as invalid
  // API use; warnings are everything else at warning level or above (loader trouble, performance
  // and best-practice notes), which is worth reading but not wrong use of Vulkan.
  std::uint32_t errors() const { return errors_.load(); }
  std::uint32_t warnings() const { return warnings_.load(); }

  // The messages counted as errors, oldest first (at most the first 64 are kept).
  std::vector<std::string> error_messages() const;

  // Whether messages are printed to stderr as they arrive (on by default). A test that provokes
  // an error on purpose turns this off to keep its output readable.
  void set_echo(bool echo) { echo_.store(echo); }

  // A create-info for a messenger that reports warnings and errors to this log. Chained into
  // VkInstanceCreateInfo it also covers vkCreateInstance and vkDestroyInstance themselves.
  VkDebugUtilsMessengerCreateInfoEXT messenger_info();

 private:
  static VKAPI_ATTR VkBool32 VKAPI_CALL callback(
      VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT types,
      const VkDebugUtilsMessengerCallbackDataEXT* data, void* user);
  void record(VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT types,
              const VkDebugUtilsMessengerCallbackDataEXT& data);

  std::atomic<std::uint32_t> errors_{0};
  std::atomic<std::uint32_t> warnings_{0};
  std::atomic<bool> echo_{true};
  mutable std::mutex mutex_;  // the layer may call back from any thread that uses Vulkan
  std::vector<std::string> error_messages_;
};

}  // namespace ddish::gpu
