#include "gpu/instance.h"

#include <cstdlib>
#include <cstring>
#include <vector>

#include "gpu/error.h"
#include "gpu/device_info.h"
#include "gpu/sanitizer_pin.h"

namespace ddish::gpu {

bool validation_requested_by_environment() {
  const char* value = std::getenv("DDISH_VALIDATION");
  return value != nullptr && value[0] != '\0' && std::strcmp(value, "0") != 0;
}

namespace {

bool instance_extension_available(const std::string& name) {
  std::uint32_t count = 0;
  if (vkEnumerateInstanceExtensionProperties(nullptr, &count, nullptr) != VK_SUCCESS) return false;
  std::vector<VkExtensionProperties> extensions(count);
  if (vkEnumerateInstanceExtensionProperties(nullptr, &count, extensions.data()) != VK_SUCCESS)
    return false;
  for (const auto& e : extensions)
    if (name == e.extensionName) return true;
  return false;
}

}  // namespace

bool validation_layer_available() {
  std::uint32_t count = 0;
  if (vkEnumerateInstanceLayerProperties(&count, nullptr) != VK_SUCCESS) return false;
  std::vector<VkLayerProperties> layers(count);
  if (vkEnumerateInstanceLayerProperties(&count, layers.data()) != VK_SUCCESS) return false;
  for (const auto& layer : layers)
    if (std::strcmp(layer.layerName, kValidationLayer) == 0) return true;
  return false;
}

Instance::Instance(const InstanceOptions& options) {
  // vkEnumerateInstanceVersion exists from loader 1.1 on; a 1.0 loader is far too old anyway.
  if (vkEnumerateInstanceVersion(&loader_version_) != VK_SUCCESS) loader_version_ = 0;
  if (loader_version_ < kRequiredApiVersion)
    throw GpuError("the Vulkan loader is version " + version_string(loader_version_) +
                   "; ddish needs Vulkan 1.3 (install libvulkan1 and mesa-vulkan-drivers)");

  const bool validation = options.validation || validation_requested_by_environment();
  if (validation && !validation_layer_available())
    throw GpuError(std::string("Vulkan validation was requested but ") + kValidationLayer +
                   " is not installed (install vulkan-validationlayers: scripts/bootstrap.sh)");

  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = options.application_name.c_str();
  app.applicationVersion = VK_MAKE_API_VERSION(0, 0, 1, 0);
  app.pEngineName = "ddish";
  app.engineVersion = VK_MAKE_API_VERSION(0, 0, 1, 0);
  app.apiVersion = kRequiredApiVersion;

  std::vector<const char*> layers;
  std::vector<const char*> extensions;
  VkDebugUtilsMessengerCreateInfoEXT messenger_info = log_->messenger_info();
  const VkValidationFeatureEnableEXT sync_feature =
      VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
  VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
  features.enabledValidationFeatureCount = 1;
  features.pEnabledValidationFeatures = &sync_feature;

  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pApplicationInfo = &app;
  if (validation) {
    layers.push_back(kValidationLayer);
    // Both extensions are provided by the layer itself, so asking for them cannot fail once the
    // layer is present.
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    info.pNext = &messenger_info;
    if (options.synchronization_validation) {
      extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
      messenger_info.pNext = &features;
    }
  }
  for (const std::string& name : options.extensions) {
    if (!instance_extension_available(name))
      throw GpuError("the Vulkan instance has no " + name + " extension");
    extensions.push_back(name.c_str());
  }
  info.enabledLayerCount = static_cast<std::uint32_t>(layers.size());
  info.ppEnabledLayerNames = layers.data();
  info.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();

  VkResult result = options.create ? options.create(info, &instance_)
                                   : vkCreateInstance(&info, nullptr, &instance_);
  if (result == VK_ERROR_INCOMPATIBLE_DRIVER)
    throw GpuError("no Vulkan driver found (install mesa-vulkan-drivers for the CPU device)");
  check(result, "vkCreateInstance");
  keep_vulkan_libraries_mapped();  // sanitizer builds: leak reports can name their frames

  if (validation) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
    messenger_info.pNext = nullptr;
    result = create != nullptr ? create(instance_, &messenger_info, nullptr, &messenger_)
                               : VK_ERROR_EXTENSION_NOT_PRESENT;
    if (result != VK_SUCCESS) {
      vkDestroyInstance(instance_, nullptr);
      check(result, "vkCreateDebugUtilsMessengerEXT");
    }
  }
}

Instance::~Instance() {
  if (messenger_ != VK_NULL_HANDLE) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy != nullptr) destroy(instance_, messenger_, nullptr);
  }
  vkDestroyInstance(instance_, nullptr);
}

}  // namespace ddish::gpu
