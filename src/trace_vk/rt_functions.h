// The ray-tracing entry points of VK_KHR_acceleration_structure and VK_KHR_ray_tracing_pipeline.
// The loader exports only core functions, so extension functions come from vkGetDeviceProcAddr,
// once per device (a device with gpu::DeviceFeatures::ray_tracing).
#pragma once

#include <vulkan/vulkan.h>

namespace ddish::gpu {
class Device;
}

namespace ddish::trace_vk {

struct RtFunctions {
  PFN_vkCreateAccelerationStructureKHR create_acceleration_structure = nullptr;
  PFN_vkDestroyAccelerationStructureKHR destroy_acceleration_structure = nullptr;
  PFN_vkGetAccelerationStructureBuildSizesKHR get_build_sizes = nullptr;
  PFN_vkCmdBuildAccelerationStructuresKHR cmd_build = nullptr;
  PFN_vkGetAccelerationStructureDeviceAddressKHR get_address = nullptr;
  PFN_vkCreateRayTracingPipelinesKHR create_pipelines = nullptr;
  PFN_vkGetRayTracingShaderGroupHandlesKHR get_group_handles = nullptr;
  PFN_vkCmdTraceRaysKHR cmd_trace_rays = nullptr;

  // Throws gpu::GpuError when the device was not created with ray tracing on, or an entry point
  // is missing.
  explicit RtFunctions(const gpu::Device& device);
};

}  // namespace ddish::trace_vk
