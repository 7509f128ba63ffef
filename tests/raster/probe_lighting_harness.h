// Runs shaders/probe_lighting_test_l{1,2,3,4}.comp: one query per invocation evaluates a function
// of probe_lighting.glsl against ProbeTextures (set 1) and BrdfTables (set 2), and the results
// come back for comparison with the CPU modules. Set 0 holds the query and result buffers.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <vulkan/vulkan.h>

#include "gpu/buffer.h"
#include "gpu/commands.h"
#include "gpu/compute_pipeline.h"
#include "gpu/device.h"
#include "gpu/error.h"
#include "gpu/handle.h"
#include "gpu/shader.h"
#include "raster/brdf_tables.h"
#include "raster/probe_descriptor_set.h"
#include "raster/probe_textures.h"

namespace ddish::raster::test {

// What a query evaluates (kind in probe_lighting_test.glsl).
enum class Kind {
  irradiance = 0,
  specular = 1,
  dfg = 2,
  ggx_zh = 3,
  l0 = 4,
  lighting_irradiance = 5,  // probe_lighting(), normal: lighting_normal(reflected direction)
  lighting_specular = 6,
  visible_l0 = 7,  // as l0, with visibility: normal b.xyz, the viewer along it
};

struct Query {
  glm::vec4 a{0.0f};  // xyz: position (x: n.v for tables); w: roughness
  glm::vec4 b{0.0f};  // xyz: normal or direction; w: kind
};

inline Query irradiance_query(glm::vec3 p, glm::vec3 n) {
  return {glm::vec4(p, 0.0f), glm::vec4(n, float(Kind::irradiance))};
}
inline Query specular_query(glm::vec3 p, glm::vec3 r, float roughness) {
  return {glm::vec4(p, roughness), glm::vec4(r, float(Kind::specular))};
}
inline Query table_query(Kind kind, float n_dot_v, float roughness) {
  return {glm::vec4(n_dot_v, 0.0f, 0.0f, roughness), glm::vec4(0.0f, 0.0f, 1.0f, float(kind))};
}
// The normal the harness passes to probe_lighting() next to reflected direction r.
inline glm::vec3 lighting_normal(glm::vec3 r) {
  return glm::normalize(glm::vec3(r.x, r.y, -r.z) + glm::vec3(0.1f, 0.2f, 0.3f));
}
inline Query lighting_query(Kind kind, glm::vec3 p, glm::vec3 r, float roughness) {
  return {glm::vec4(p, roughness), glm::vec4(r, float(kind))};
}
inline Query l0_query(glm::vec3 p) {
  return {glm::vec4(p, 0.0f), glm::vec4(0.0f, 0.0f, 1.0f, float(Kind::l0))};
}

inline Query visible_l0_query(glm::vec3 p, glm::vec3 n) {
  return {glm::vec4(p, 0.0f), glm::vec4(n, float(Kind::visible_l0))};
}

class Harness {
 public:
  Harness(const gpu::Device& device, const ProbeTextures& probes, const BrdfTables& brdf,
          int order)
      : device_(&device), probes_(&probes), brdf_(&brdf) {
    const VkDevice vk = device.handle();
    const VkDescriptorSetLayoutBinding io[] = {
        {0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
        {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
    };
    io_ = OwnedDescriptorSet(vk, io);
    const VkDescriptorSetLayout sets[] = {io_.layout(), probes.layout(), brdf.layout()};
    const VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, 4};
    VkPipelineLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layout_info.setLayoutCount = 3;
    layout_info.pSetLayouts = sets;
    layout_info.pushConstantRangeCount = 1;
    layout_info.pPushConstantRanges = &push;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    gpu::check(vkCreatePipelineLayout(vk, &layout_info, nullptr, &layout), "pipeline layout");
    layout_ = {vk, layout};
    const auto shader = gpu::ShaderModule::load(
        device, "probe_lighting_test_l" + std::to_string(order) + ".comp");
    VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = shader.handle();
    info.stage.pName = "main";
    info.layout = layout;
    VkPipeline pipeline = VK_NULL_HANDLE;
    gpu::check(vkCreateComputePipelines(vk, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline),
               "compute pipeline");
    pipeline_ = {vk, pipeline};
  }

  std::vector<glm::vec4> run(gpu::CommandRunner& runner, const std::vector<Query>& queries) {
    const auto count = std::uint32_t(queries.size());
    gpu::Buffer in(*device_, sizeof(Query) * count, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                   gpu::MemoryUse::upload);
    gpu::Buffer out(*device_, sizeof(glm::vec4) * count, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                    gpu::MemoryUse::readback);
    in.write(queries.data(), sizeof(Query) * count);
    const VkDescriptorBufferInfo infos[] = {in.descriptor(), out.descriptor()};
    for (std::uint32_t b = 0; b < 2; ++b) {
      VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
      write.dstSet = io_.set();
      write.dstBinding = b;
      write.descriptorCount = 1;
      write.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
      write.pBufferInfo = &infos[b];
      vkUpdateDescriptorSets(device_->handle(), 1, &write, 0, nullptr);
    }
    runner.run([&](VkCommandBuffer cmd) {
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_.get());
      const VkDescriptorSet sets[] = {io_.set(), probes_->set(), brdf_->set()};
      vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.get(), 0, 3, sets, 0,
                              nullptr);
      vkCmdPushConstants(cmd, layout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, 4, &count);
      vkCmdDispatch(cmd, gpu::group_count(count, 64), 1, 1);
      gpu::memory_barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                          VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
    });
    return out.read<glm::vec4>(count);
  }

 private:
  const gpu::Device* device_;
  const ProbeTextures* probes_;
  const BrdfTables* brdf_;
  OwnedDescriptorSet io_;
  gpu::DeviceHandle<VkPipelineLayout, vkDestroyPipelineLayout> layout_;
  gpu::DeviceHandle<VkPipeline, vkDestroyPipeline> pipeline_;
};

}  // namespace ddish::raster::test
