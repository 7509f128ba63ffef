#include "trace_vk/rt_functions.h"

#include <string>

#include "gpu/device.h"
#include "gpu/error.h"

namespace ddish::trace_vk {

namespace {

template <typename F>
void load(VkDevice device, const char* name, F& out) {
  out = reinterpret_cast<F>(vkGetDeviceProcAddr(device, name));
  if (!out) throw gpu::GpuError(std::string("the Vulkan device has no ") + name);
}

}  // namespace

RtFunctions::RtFunctions(const gpu::Device& device) {
  if (!device.features().ray_tracing)
    throw gpu::GpuError(device.info().name + " was opened without Vulkan ray tracing");
  const VkDevice d = device.handle();
  load(d, "vkCreateAccelerationStructureKHR", create_acceleration_structure);
  load(d, "vkDestroyAccelerationStructureKHR", destroy_acceleration_structure);
  load(d, "vkGetAccelerationStructureBuildSizesKHR", get_build_sizes);
  load(d, "vkCmdBuildAccelerationStructuresKHR", cmd_build);
  load(d, "vkGetAccelerationStructureDeviceAddressKHR", get_address);
  load(d, "vkCreateRayTracingPipelinesKHR", create_pipelines);
  load(d, "vkGetRayTracingShaderGroupHandlesKHR", get_group_handles);
  load(d, "vkCmdTraceRaysKHR", cmd_trace_rays);
}

}  // namespace ddish::trace_vk
