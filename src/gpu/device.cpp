#include "gpu/device.h"

#include <algorithm>

#include "gpu/error.h"
#include "gpu/instance.h"

namespace ddish::gpu {

namespace {

// The full feature chain of a Vulkan 1.3 device. The same layout serves to query what the device
// has and, after pruning, to say what to enable: enabling a feature is asking for it by value.
struct FeatureChain {
  VkPhysicalDeviceFeatures2 core{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  VkPhysicalDeviceVulkan11Features v11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES};
  VkPhysicalDeviceVulkan12Features v12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  VkPhysicalDeviceVulkan13Features v13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};

  FeatureChain() { link(); }
  FeatureChain(const FeatureChain&) = delete;
  FeatureChain& operator=(const FeatureChain&) = delete;
  void link() {
    core.pNext = &v11;
    v11.pNext = &v12;
    v12.pNext = &v13;
    v13.pNext = nullptr;
  }
};

// Copies `available` into `enable` and into the reported flag: on only where present.
void want(VkBool32 available, VkBool32& enable, bool& reported) {
  enable = available;
  reported = available == VK_TRUE;
}

DeviceFeatures choose_features(const FeatureChain& has, FeatureChain& enable) {
  DeviceFeatures f;
  const VkPhysicalDeviceFeatures& h = has.core.features;
  VkPhysicalDeviceFeatures& e = enable.core.features;
  want(has.v11.multiview, enable.v11.multiview, f.multiview);
  want(has.v12.shaderOutputLayer, enable.v12.shaderOutputLayer, f.shader_output_layer);
  want(has.v12.shaderOutputViewportIndex, enable.v12.shaderOutputViewportIndex,
       f.shader_output_viewport_index);
  want(h.multiViewport, e.multiViewport, f.multi_viewport);
  want(h.samplerAnisotropy, e.samplerAnisotropy, f.sampler_anisotropy);
  want(h.fillModeNonSolid, e.fillModeNonSolid, f.fill_mode_non_solid);
  want(h.depthClamp, e.depthClamp, f.depth_clamp);
  want(h.multiDrawIndirect, e.multiDrawIndirect, f.multi_draw_indirect);
  want(h.drawIndirectFirstInstance, e.drawIndirectFirstInstance, f.draw_indirect_first_instance);
  want(h.sampleRateShading, e.sampleRateShading, f.sample_rate_shading);
  want(h.geometryShader, e.geometryShader, f.geometry_shader);
  want(h.independentBlend, e.independentBlend, f.independent_blend);
  want(h.textureCompressionBC, e.textureCompressionBC, f.texture_compression_bc);
  want(h.shaderInt16, e.shaderInt16, f.shader_int16);
  want(has.v12.shaderFloat16, enable.v12.shaderFloat16, f.shader_float16);
  want(has.v11.storageBuffer16BitAccess, enable.v11.storageBuffer16BitAccess,
       f.storage_buffer_16bit_access);
  want(has.v12.hostQueryReset, enable.v12.hostQueryReset, f.host_query_reset);
  want(has.v12.timelineSemaphore, enable.v12.timelineSemaphore, f.timeline_semaphore);
  want(has.v13.synchronization2, enable.v13.synchronization2, f.synchronization2);
  want(has.v13.dynamicRendering, enable.v13.dynamicRendering, f.dynamic_rendering);
  want(has.v13.maintenance4, enable.v13.maintenance4, f.maintenance4);
  want(has.v12.shaderSampledImageArrayNonUniformIndexing,
       enable.v12.shaderSampledImageArrayNonUniformIndexing, f.sampled_image_non_uniform_indexing);
  return f;
}

std::uint32_t chosen_device(const std::vector<DeviceInfo>& devices, const DeviceOptions& options) {
  if (options.physical == VK_NULL_HANDLE) return select_device(devices, options.index);
  for (std::uint32_t i = 0; i < devices.size(); ++i)
    if (devices[i].handle == options.physical) {
      if (!devices[i].queue_family)
        throw GpuError(devices[i].name + " has no graphics and compute queue");
      return i;
    }
  throw GpuError("the Vulkan physical device asked for is not one of this instance's");
}

}  // namespace

Device::Device(const Instance& instance, const DeviceOptions& options) : instance_(instance) {
  std::vector<DeviceInfo> devices = enumerate_devices(instance);
  info_ = devices[chosen_device(devices, options)];
  vkGetPhysicalDeviceMemoryProperties(info_.handle, &memory_);

  FeatureChain available;
  vkGetPhysicalDeviceFeatures2(info_.handle, &available.core);
  FeatureChain enabled;
  features_ = choose_features(available, enabled);

  const float priority = 1.0f;
  VkDeviceQueueCreateInfo queue_info{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queue_info.queueFamilyIndex = *info_.queue_family;
  queue_info.queueCount = 1;
  queue_info.pQueuePriorities = &priority;

  std::vector<std::string> names = options.extensions;
  // Ray tracing: the extensions and their features, chained after the core ones.
  VkPhysicalDeviceAccelerationStructureFeaturesKHR acceleration{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR};
  VkPhysicalDeviceRayTracingPipelineFeaturesKHR pipeline{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_TRACING_PIPELINE_FEATURES_KHR};
  if (options.ray_tracing && info_.ray_tracing) {
    acceleration.accelerationStructure = VK_TRUE;
    pipeline.rayTracingPipeline = VK_TRUE;
    acceleration.pNext = &pipeline;
    enabled.v13.pNext = &acceleration;
    enabled.v12.bufferDeviceAddress = VK_TRUE;
    for (const std::string& name : ray_tracing_extensions()) names.push_back(name);
    features_.ray_tracing = true;
  }

  constexpr const char* kPostDepthCoverage = "VK_EXT_post_depth_coverage";
  if (device_extension_available(info_.handle, kPostDepthCoverage) &&
      std::find(names.begin(), names.end(), kPostDepthCoverage) == names.end()) {
    names.emplace_back(kPostDepthCoverage);
    features_.post_depth_coverage = true;
  }

  std::vector<const char*> extensions;
  for (const std::string& name : names) {
    if (!device_extension_available(info_.handle, name))
      throw GpuError(info_.name + " has no " + name + " extension");
    extensions.push_back(name.c_str());
  }

  VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  info.pNext = &enabled.core;  // features go through the chain, so pEnabledFeatures stays null
  info.queueCreateInfoCount = 1;
  info.pQueueCreateInfos = &queue_info;
  info.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  check(options.create ? options.create(info_.handle, info, &device_)
                       : vkCreateDevice(info_.handle, &info, nullptr, &device_),
        "vkCreateDevice on " + info_.name);
  vkGetDeviceQueue(device_, *info_.queue_family, 0, &queue_);
}

Device::~Device() {
  // Objects still in flight must finish before their device goes away.
  vkDeviceWaitIdle(device_);
  vkDestroyDevice(device_, nullptr);
}

void Device::wait_idle() const { check(vkDeviceWaitIdle(device_), "vkDeviceWaitIdle"); }

}  // namespace ddish::gpu
