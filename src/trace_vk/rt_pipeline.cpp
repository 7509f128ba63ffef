// VkProbeTracer's ray-tracing pipeline (probe_trace.rgen/.rchit/.rahit/.rmiss and the shadow
// pair), its shader binding table, and the descriptors that bind the scene and the update's
// buffers to it and to the projection (probe_project.comp).
#include <array>
#include <cstring>

#include "gpu/error.h"
#include "gpu/shader.h"
#include "trace_vk/vk_probe_tracer_impl.h"

namespace ddish::trace_vk {

void VkProbeTracer::Impl::make_rt_pipeline() {
  const VkDevice d = device.handle();
  std::array<VkDescriptorSetLayoutBinding, kRtBindings> bindings{};
  for (std::uint32_t i = 0; i < kRtBindings; ++i) {
    bindings[i].binding = i;
    bindings[i].descriptorType =
        i == 0 ? VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    bindings[i].descriptorCount = 1;
    bindings[i].stageFlags = VK_SHADER_STAGE_RAYGEN_BIT_KHR | VK_SHADER_STAGE_ANY_HIT_BIT_KHR;
  }
  VkDescriptorSetLayoutCreateInfo set_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  set_info.bindingCount = kRtBindings;
  set_info.pBindings = bindings.data();
  VkDescriptorSetLayout sl = VK_NULL_HANDLE;
  gpu::check(vkCreateDescriptorSetLayout(d, &set_info, nullptr, &sl), "vkCreateDescriptorSetLayout");
  set_layout = {d, sl};

  const VkPushConstantRange push{VK_SHADER_STAGE_RAYGEN_BIT_KHR, 0, sizeof(TraceParams)};
  VkPipelineLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layout_info.setLayoutCount = 1;
  layout_info.pSetLayouts = &sl;
  layout_info.pushConstantRangeCount = 1;
  layout_info.pPushConstantRanges = &push;
  VkPipelineLayout pl = VK_NULL_HANDLE;
  gpu::check(vkCreatePipelineLayout(d, &layout_info, nullptr, &pl), "vkCreatePipelineLayout");
  pipeline_layout = {d, pl};

  const gpu::ShaderModule raygen = gpu::ShaderModule::load(device, "probe_trace.rgen");
  const gpu::ShaderModule miss = gpu::ShaderModule::load(device, "probe_trace.rmiss");
  const gpu::ShaderModule shadow_miss = gpu::ShaderModule::load(device, "probe_shadow.rmiss");
  const gpu::ShaderModule closest = gpu::ShaderModule::load(device, "probe_trace.rchit");
  const gpu::ShaderModule any = gpu::ShaderModule::load(device, "probe_trace.rahit");
  const gpu::ShaderModule shadow_any = gpu::ShaderModule::load(device, "probe_shadow.rahit");
  std::array<VkPipelineShaderStageCreateInfo, 6> stages{};
  const std::array<std::pair<VkShaderStageFlagBits, VkShaderModule>, 6> modules = {{
      {VK_SHADER_STAGE_RAYGEN_BIT_KHR, raygen.handle()},
      {VK_SHADER_STAGE_MISS_BIT_KHR, miss.handle()},
      {VK_SHADER_STAGE_MISS_BIT_KHR, shadow_miss.handle()},
      {VK_SHADER_STAGE_CLOSEST_HIT_BIT_KHR, closest.handle()},
      {VK_SHADER_STAGE_ANY_HIT_BIT_KHR, any.handle()},
      {VK_SHADER_STAGE_ANY_HIT_BIT_KHR, shadow_any.handle()},
  }};
  for (std::size_t i = 0; i < stages.size(); ++i) {
    stages[i] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    stages[i].stage = modules[i].first;
    stages[i].module = modules[i].second;
    stages[i].pName = "main";
  }
  // Groups: raygen, path miss, shadow miss, then two hit groups: path rays (closest hit and
  // any-hit, SBT offset 0) and shadow rays (any-hit only, SBT offset 1).
  std::array<VkRayTracingShaderGroupCreateInfoKHR, 5> groups{};
  for (std::uint32_t i = 0; i < groups.size(); ++i) {
    groups[i] = {VK_STRUCTURE_TYPE_RAY_TRACING_SHADER_GROUP_CREATE_INFO_KHR};
    groups[i].type = i < 3 ? VK_RAY_TRACING_SHADER_GROUP_TYPE_GENERAL_KHR
                           : VK_RAY_TRACING_SHADER_GROUP_TYPE_TRIANGLES_HIT_GROUP_KHR;
    groups[i].generalShader = i < 3 ? i : VK_SHADER_UNUSED_KHR;
    groups[i].closestHitShader = i == 3 ? 3 : VK_SHADER_UNUSED_KHR;
    groups[i].anyHitShader = i == 3 ? 4 : i == 4 ? 5 : VK_SHADER_UNUSED_KHR;
    groups[i].intersectionShader = VK_SHADER_UNUSED_KHR;
  }
  VkRayTracingPipelineCreateInfoKHR info{VK_STRUCTURE_TYPE_RAY_TRACING_PIPELINE_CREATE_INFO_KHR};
  info.stageCount = static_cast<std::uint32_t>(stages.size());
  info.pStages = stages.data();
  info.groupCount = static_cast<std::uint32_t>(groups.size());
  info.pGroups = groups.data();
  info.maxPipelineRayRecursionDepth = 1;  // only the ray generation shader traces
  info.layout = pl;
  VkPipeline p = VK_NULL_HANDLE;
  gpu::check(rt.create_pipelines(d, VK_NULL_HANDLE, VK_NULL_HANDLE, 1, &info, nullptr, &p),
             "vkCreateRayTracingPipelinesKHR");
  pipeline = {d, p};

  // The shader binding table: raygen, the two misses, the hit group, each region aligned.
  VkPhysicalDeviceRayTracingPipelinePropertiesKHR rtp{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_TRACING_PIPELINE_PROPERTIES_KHR};
  VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  props.pNext = &rtp;
  vkGetPhysicalDeviceProperties2(device.physical(), &props);
  const VkDeviceSize handle_size = rtp.shaderGroupHandleSize;
  const VkDeviceSize base = rtp.shaderGroupBaseAlignment;
  const VkDeviceSize stride = align_up(handle_size, rtp.shaderGroupHandleAlignment);
  std::vector<std::uint8_t> handles(groups.size() * handle_size);
  gpu::check(rt.get_group_handles(d, p, 0, static_cast<std::uint32_t>(groups.size()), handles.size(), handles.data()),
             "vkGetRayTracingShaderGroupHandlesKHR");
  const VkDeviceSize raygen_size = align_up(stride, base);
  const VkDeviceSize miss_offset = raygen_size;
  const VkDeviceSize miss_size = align_up(2 * stride, base);
  const VkDeviceSize hit_offset = miss_offset + miss_size;
  const VkDeviceSize hit_size = align_up(2 * stride, base);
  sbt = std::make_unique<gpu::Buffer>(
      device, hit_offset + hit_size + base,
      VK_BUFFER_USAGE_SHADER_BINDING_TABLE_BIT_KHR | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT, gpu::MemoryUse::upload);
  const VkDeviceAddress address = align_up(sbt->device_address(), base);
  const VkDeviceSize shift = address - sbt->device_address();
  sbt->write(handles.data() + 0 * handle_size, handle_size, shift);
  sbt->write(handles.data() + 1 * handle_size, handle_size, shift + miss_offset);
  sbt->write(handles.data() + 2 * handle_size, handle_size, shift + miss_offset + stride);
  sbt->write(handles.data() + 3 * handle_size, handle_size, shift + hit_offset);
  sbt->write(handles.data() + 4 * handle_size, handle_size, shift + hit_offset + stride);
  raygen_region = {address, raygen_size, raygen_size};
  miss_region = {address + miss_offset, stride, miss_size};
  hit_region = {address + hit_offset, stride, hit_size};

  const std::array<VkDescriptorPoolSize, 2> sizes = {{{VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR, 1},
                                                      {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kRtBindings - 1}}};
  VkDescriptorPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pool_info.maxSets = 1;
  pool_info.poolSizeCount = static_cast<std::uint32_t>(sizes.size());
  pool_info.pPoolSizes = sizes.data();
  VkDescriptorPool dp = VK_NULL_HANDLE;
  gpu::check(vkCreateDescriptorPool(d, &pool_info, nullptr, &dp), "vkCreateDescriptorPool");
  pool = {d, dp};
  VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  alloc.descriptorPool = dp;
  alloc.descriptorSetCount = 1;
  alloc.pSetLayouts = &sl;
  gpu::check(vkAllocateDescriptorSets(d, &alloc, &set), "vkAllocateDescriptorSets");
}

void VkProbeTracer::Impl::write_descriptors() {
  const VkAccelerationStructureKHR tlas = acceleration->tlas();
  VkWriteDescriptorSetAccelerationStructureKHR as{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET_ACCELERATION_STRUCTURE_KHR};
  as.accelerationStructureCount = 1;
  as.pAccelerationStructures = &tlas;
  const std::array<const gpu::Buffer*, kRtBindings - 1> buffers = {
      paths.get(), work.get(), &vertices, &indices, &meshes, &instances, &materials, &emissive, &lights, &albedo,
      lattice.get(), &textures, &texture_levels, &texels, &environment_texels, &environment_cdf, distances.get()};
  std::array<VkDescriptorBufferInfo, kRtBindings - 1> infos{};
  std::array<VkWriteDescriptorSet, kRtBindings> writes{};
  writes[0] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  writes[0].pNext = &as;
  writes[0].dstSet = set;
  writes[0].dstBinding = 0;
  writes[0].descriptorCount = 1;
  writes[0].descriptorType = VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR;
  for (std::uint32_t i = 1; i < kRtBindings; ++i) {
    infos[i - 1] = buffers[i - 1]->descriptor();
    writes[i] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    writes[i].dstSet = set;
    writes[i].dstBinding = i;
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writes[i].pBufferInfo = &infos[i - 1];
  }
  vkUpdateDescriptorSets(device.handle(), kRtBindings, writes.data(), 0, nullptr);
  project->bind_buffers({paths.get(), lattice.get(), work.get(), blends.get(), coefficients.get(), results.get(),
                         distances.get(), moments.get()});
}

}  // namespace ddish::trace_vk
