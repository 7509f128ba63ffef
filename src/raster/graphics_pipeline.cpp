#include "raster/graphics_pipeline.h"

#include <array>

#include "gpu/device.h"
#include "gpu/error.h"
#include "raster/gpu_meshes.h"

namespace ddish::raster {

Pipeline make_graphics_pipeline(const gpu::Device& device, const GraphicsPipelineDesc& desc) {
  // Every constant is 32 bits (VkBool32 or uint32_t): the bools, then the integers.
  std::vector<std::uint32_t> values(desc.fragment_constants.begin(), desc.fragment_constants.end());
  std::vector<VkSpecializationMapEntry> entries;
  for (std::uint32_t i = 0; i < desc.fragment_constants.size(); ++i)
    entries.push_back({i, i * 4u, 4u});
  for (const auto& [id, value] : desc.fragment_int_constants) {
    entries.push_back({id, static_cast<std::uint32_t>(values.size()) * 4u, 4u});
    values.push_back(value);
  }
  VkSpecializationInfo spec{static_cast<std::uint32_t>(entries.size()), entries.data(),
                            values.size() * sizeof(std::uint32_t), values.data()};

  std::vector<VkPipelineShaderStageCreateInfo> stages;
  VkPipelineShaderStageCreateInfo vs{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  vs.stage = VK_SHADER_STAGE_VERTEX_BIT;
  vs.module = desc.vertex;
  vs.pName = "main";
  stages.push_back(vs);
  if (desc.fragment != VK_NULL_HANDLE) {
    VkPipelineShaderStageCreateInfo fs{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    fs.stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    fs.module = desc.fragment;
    fs.pName = "main";
    fs.pSpecializationInfo = entries.empty() ? nullptr : &spec;
    stages.push_back(fs);
  }

  const VkVertexInputBindingDescription binding = GpuMeshes::binding();
  const auto attributes = GpuMeshes::attributes();
  VkPipelineVertexInputStateCreateInfo input{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  if (!desc.fullscreen) {
    input.vertexBindingDescriptionCount = 1;
    input.pVertexBindingDescriptions = &binding;
    input.vertexAttributeDescriptionCount =
        desc.position_only ? 1u : static_cast<std::uint32_t>(attributes.size());
    input.pVertexAttributeDescriptions = attributes.data();
  }

  VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  viewport.viewportCount = 1;
  viewport.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  raster.cullMode = VK_CULL_MODE_BACK_BIT;  // dynamic; this is only the initial value
  raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  raster.lineWidth = 1.0f;
  raster.depthBiasEnable = desc.depth_bias ? VK_TRUE : VK_FALSE;
  // Shadow maps: a small constant bias; the receiver's normal offset in surface_lighting.glsl
  // (larger at grazing light) removes acne. No slope-scaled bias: it pushes a caster seen at
  // grazing light back by 1.5x its depth slope (~5x a texel at 12 degrees), so light leaked
  // where such a caster meets the surface it shadows (the Breakfast room's back wall, lit by
  // the sun from behind, let light onto the side wall and the picture along their contact
  // lines, issue 8; tests/raster/raster_bias_test.cpp).
  raster.depthBiasConstantFactor = desc.depth_bias ? 1.0f : 0.0f;
  raster.depthBiasSlopeFactor = 0.0f;
  VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  multisample.rasterizationSamples = desc.samples;
  if (desc.sample_shading) {
    multisample.sampleShadingEnable = VK_TRUE;
    multisample.minSampleShading = 1.0f;
  }
  VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  depth.depthTestEnable = desc.fullscreen ? VK_FALSE : VK_TRUE;
  depth.depthWriteEnable = desc.depth_write && !desc.alpha_blend ? VK_TRUE : VK_FALSE;
  depth.depthCompareOp = VK_COMPARE_OP_LESS_OR_EQUAL;
  VkPipelineColorBlendAttachmentState blend_attachment{};
  if (desc.color_write)
    blend_attachment.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                                      VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
  if (desc.alpha_blend) {
    blend_attachment.blendEnable = VK_TRUE;
    blend_attachment.srcColorBlendFactor = VK_BLEND_FACTOR_SRC_ALPHA;
    blend_attachment.dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
    blend_attachment.colorBlendOp = VK_BLEND_OP_ADD;
    // The target's alpha stays 1 (coverage of what is behind): alpha' = alpha + 1 * (1 - alpha).
    blend_attachment.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
    blend_attachment.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
    blend_attachment.alphaBlendOp = VK_BLEND_OP_ADD;
  }
  VkPipelineColorBlendStateCreateInfo blend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  const bool color = desc.color_format != VK_FORMAT_UNDEFINED;
  blend.attachmentCount = color ? 1u : 0u;
  blend.pAttachments = &blend_attachment;
  const std::array<VkDynamicState, 4> dynamic_states{VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR,
                                                     VK_DYNAMIC_STATE_CULL_MODE, VK_DYNAMIC_STATE_FRONT_FACE};
  VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dynamic.dynamicStateCount = static_cast<std::uint32_t>(dynamic_states.size());
  dynamic.pDynamicStates = dynamic_states.data();

  VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
  rendering.viewMask = desc.view_mask;
  rendering.colorAttachmentCount = color ? 1u : 0u;
  rendering.pColorAttachmentFormats = &desc.color_format;
  rendering.depthAttachmentFormat = desc.depth_format;

  VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  info.pNext = &rendering;
  info.stageCount = static_cast<std::uint32_t>(stages.size());
  info.pStages = stages.data();
  info.pVertexInputState = &input;
  info.pInputAssemblyState = &assembly;
  info.pViewportState = &viewport;
  info.pRasterizationState = &raster;
  info.pMultisampleState = &multisample;
  info.pDepthStencilState = &depth;
  info.pColorBlendState = &blend;
  info.pDynamicState = &dynamic;
  info.layout = desc.layout;
  VkPipeline pipeline = VK_NULL_HANDLE;
  gpu::check(vkCreateGraphicsPipelines(device.handle(), VK_NULL_HANDLE, 1, &info, nullptr, &pipeline),
             "vkCreateGraphicsPipelines");
  return Pipeline(device.handle(), pipeline);
}

PipelineLayout make_pipeline_layout(const gpu::Device& device,
                                    std::span<const VkDescriptorSetLayout> sets,
                                    std::uint32_t push_constant_bytes) {
  const VkPushConstantRange range{VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                                  push_constant_bytes};
  VkPipelineLayoutCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  info.setLayoutCount = static_cast<std::uint32_t>(sets.size());
  info.pSetLayouts = sets.data();
  info.pushConstantRangeCount = push_constant_bytes > 0 ? 1u : 0u;
  info.pPushConstantRanges = &range;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  gpu::check(vkCreatePipelineLayout(device.handle(), &info, nullptr, &layout), "vkCreatePipelineLayout");
  return PipelineLayout(device.handle(), layout);
}

void set_viewport(VkCommandBuffer cmd, std::uint32_t width, std::uint32_t height) {
  const VkViewport viewport{0.0f, 0.0f, float(width), float(height), 0.0f, 1.0f};
  const VkRect2D scissor{{0, 0}, {width, height}};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &scissor);
}

}  // namespace ddish::raster
