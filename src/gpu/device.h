// The logical device: one graphics+compute queue on the selected physical device, with the
// optional features the renderer can use switched on where the device has them.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "gpu/device_info.h"

namespace ddish::gpu {

class Instance;

struct DeviceOptions {
  std::optional<std::uint32_t> index;  // --device N; default: see default_device_index()
  // Set: this physical device and no other (the one an OpenXR runtime names); overrides index.
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  // Device extensions beyond the renderer's (VK_KHR_swapchain for a window). A missing one
  // throws GpuError naming it and the device.
  std::vector<std::string> extensions;
  // Switch Vulkan ray tracing on where the device has it (DeviceInfo::ray_tracing): its
  // extensions, rayTracingPipeline, accelerationStructure and bufferDeviceAddress. Off by
  // default so that the rasterizer's devices stay as they were; the GPU probe tracer asks.
  bool ray_tracing = false;
  // Set: called instead of vkCreateDevice with the create info built here (OpenXR's
  // xrCreateVulkanDeviceKHR). The device is still destroyed here.
  std::function<VkResult(VkPhysicalDevice, const VkDeviceCreateInfo&, VkDevice*)> create;
};

// Optional features, each true only when the device has it (and it was therefore enabled).
// Callers branch on these instead of assuming a feature: lavapipe, for one, has no
// descriptor indexing, and a GPU may lack shaderOutputLayer.
struct DeviceFeatures {
  bool multiview = false;                    // VK_KHR_multiview (core 1.1): N views per pass
  bool shader_output_layer = false;          // gl_Layer from vertex shaders
  bool shader_output_viewport_index = false; // gl_ViewportIndex from vertex shaders
  bool multi_viewport = false;
  bool sampler_anisotropy = false;
  bool fill_mode_non_solid = false;  // wireframe debugging
  bool depth_clamp = false;          // shadow-map pancaking
  bool multi_draw_indirect = false;
  bool draw_indirect_first_instance = false;
  bool sample_rate_shading = false;
  bool independent_blend = false;
  bool texture_compression_bc = false;
  bool shader_int16 = false;
  bool shader_float16 = false;
  bool storage_buffer_16bit_access = false;  // fp16 SH probe data read straight from buffers
  bool host_query_reset = false;
  bool timeline_semaphore = false;
  bool synchronization2 = false;
  bool dynamic_rendering = false;  // rendering without VkRenderPass objects
  // Required by every 1.3 device, and needed: glslang's vulkan1.3 target writes the work-group
  // size as LocalSizeId, which is only valid with maintenance4 on.
  bool maintenance4 = false;
  // Ray-tracing pipelines, acceleration structures and buffer device addresses
  // (DeviceOptions::ray_tracing on a device that has them).
  bool ray_tracing = false;
  // VK_EXT_post_depth_coverage: a fragment shader with early tests may read which samples
  // passed the depth test (gl_SampleMaskIn), what the forward pass's depth prepass needs
  // (raster/forward_pass.h). Lavapipe has it.
  bool post_depth_coverage = false;
  // shaderSampledImageArrayNonUniformIndexing (core 1.2): a shader may pick a texture from an
  // array per pixel, what the visibility pass's material reads need (raster/visibility_pass.h).
  // Mesa 22's lavapipe lacks it, Mesa 25's has it.
  bool sampled_image_non_uniform_indexing = false;
  // geometryShader: ddish draws no geometry shaders, but a fragment shader that reads
  // gl_PrimitiveID (the visibility pass's ids) declares the Geometry capability, which needs it.
  bool geometry_shader = false;
};

class Device {
 public:
  // Opens options.index or the default device. Throws GpuError when there is no usable device or
  // the index is out of range.
  explicit Device(const Instance& instance, const DeviceOptions& options = {});
  ~Device();
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;

  VkDevice handle() const { return device_; }
  VkPhysicalDevice physical() const { return info_.handle; }
  VkQueue queue() const { return queue_; }
  std::uint32_t queue_family() const { return *info_.queue_family; }
  const DeviceInfo& info() const { return info_; }
  const DeviceFeatures& features() const { return features_; }
  const VkPhysicalDeviceLimits& limits() const { return info_.limits; }
  const VkPhysicalDeviceMemoryProperties& memory_properties() const { return memory_; }
  const Instance& instance() const { return instance_; }

  // Blocks until the queue has finished everything submitted.
  void wait_idle() const;

 private:
  const Instance& instance_;
  DeviceInfo info_;
  DeviceFeatures features_;
  VkPhysicalDeviceMemoryProperties memory_{};
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
};

}  // namespace ddish::gpu
