// Graphics pipelines for dynamic rendering (Vulkan 1.3, no VkRenderPass objects): the one
// construction shared by the shadow pass and the forward pass. Viewport, scissor, cull mode and
// front face are dynamic state, so one pipeline draws single- and double-sided materials and
// mirrored instances alike.
#pragma once

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include <vulkan/vulkan.h>

#include "gpu/handle.h"

namespace ddish::gpu {
class Device;
}

namespace ddish::raster {

using Pipeline = gpu::DeviceHandle<VkPipeline, vkDestroyPipeline>;
using PipelineLayout = gpu::DeviceHandle<VkPipelineLayout, vkDestroyPipelineLayout>;

struct GraphicsPipelineDesc {
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VkShaderModule vertex = VK_NULL_HANDLE;
  VkShaderModule fragment = VK_NULL_HANDLE;  // none: depth only
  std::vector<VkBool32> fragment_constants;  // specialization constants 0..n-1 (bools)
  // Further 32-bit integer specialization constants of the fragment stage: (constant id, value).
  std::vector<std::pair<std::uint32_t, std::uint32_t>> fragment_int_constants;
  bool position_only = false;                // vertex input: location 0 only
  VkFormat color_format = VK_FORMAT_UNDEFINED;
  VkFormat depth_format = VK_FORMAT_UNDEFINED;
  VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
  bool sample_shading = false;  // shade every sample (needs the sampleRateShading feature)
  bool depth_bias = false;      // constant depth bias for shadow maps
  std::uint32_t view_mask = 0;  // multiview: one bit per view rendered by one draw
  // Transparent (glTF BLEND) draws: colour = src * alpha + dst * (1 - alpha), depth tested but
  // not written, so sorted layers behind one another all blend.
  bool alpha_blend = false;
  // false: depth tested but not written (the shading pass after a depth prepass).
  bool depth_write = true;
  // false: no colour written (a depth prepass drawn in the colour pass).
  bool color_write = true;
  // No vertex input, no depth test: one full-screen triangle (fullscreen.vert).
  bool fullscreen = false;
};

Pipeline make_graphics_pipeline(const gpu::Device& device, const GraphicsPipelineDesc& desc);

// A layout of the given set layouts and one push-constant block visible to every stage.
PipelineLayout make_pipeline_layout(const gpu::Device& device,
                                    std::span<const VkDescriptorSetLayout> sets,
                                    std::uint32_t push_constant_bytes);

// Viewport and scissor covering width x height, for the dynamic state of every pass.
void set_viewport(VkCommandBuffer cmd, std::uint32_t width, std::uint32_t height);

}  // namespace ddish::raster
