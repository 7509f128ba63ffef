#include "raster/shadow_maps.h"

#include <algorithm>
#include <array>
#include <string>

#include "gpu/commands.h"
#include "gpu/device.h"
#include "gpu/error.h"
#include "gpu/shader.h"
#include "raster/gpu_meshes.h"
#include "raster/gpu_types.h"
#include "raster/material_textures.h"
#include "scene/scene.h"

namespace ddish::raster {

ShadowMaps::ShadowMaps(const gpu::Device& device, gpu::CommandRunner& runner, std::uint32_t map_size,
                       std::uint32_t capacity, VkDescriptorSetLayout frame_layout,
                       VkDescriptorSetLayout material_layout, bool alpha_test)
    : map_size_(map_size),
      image_(device, {.width = map_size, .height = map_size, .layers = std::max(capacity, 1u),
                      .format = kFormat,
                      .usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT}) {
  for (std::uint32_t i = 0; i < image_.desc().layers; ++i) layer_views_.push_back(image_.make_view(i, 1));
  // The shader samples a sampler2DArrayShadow, which needs an array view even of one layer
  // (Image::view() is a plain 2D view then).
  VkImageViewCreateInfo view_info{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  view_info.image = image_.handle();
  view_info.viewType = VK_IMAGE_VIEW_TYPE_2D_ARRAY;
  view_info.format = kFormat;
  view_info.subresourceRange = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, 0, image_.desc().layers};
  VkImageView array_view = VK_NULL_HANDLE;
  gpu::check(vkCreateImageView(device.handle(), &view_info, nullptr, &array_view), "vkCreateImageView");
  array_view_ = gpu::ImageView(device.handle(), array_view);

  VkFormatProperties props{};
  vkGetPhysicalDeviceFormatProperties(device.physical(), kFormat, &props);
  linear_ = (props.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT) != 0;
  VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  info.magFilter = info.minFilter = linear_ ? VK_FILTER_LINEAR : VK_FILTER_NEAREST;
  info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  // Outside the map: lit (white border at depth 1 passes every comparison).
  info.addressModeU = info.addressModeV = info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER;
  info.borderColor = VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE;
  info.compareEnable = VK_TRUE;
  info.compareOp = VK_COMPARE_OP_LESS_OR_EQUAL;  // lit when the reference is not behind the map
  VkSampler sampler = VK_NULL_HANDLE;
  gpu::check(vkCreateSampler(device.handle(), &info, nullptr, &sampler), "vkCreateSampler");
  sampler_ = {device.handle(), sampler};

  const std::array<VkDescriptorSetLayout, 2> sets{frame_layout, material_layout};
  layout_ = make_pipeline_layout(device, sets, sizeof(DrawConstants));
  const gpu::ShaderModule vertex = gpu::ShaderModule::load(device, "shadow.vert");
  GraphicsPipelineDesc desc;
  desc.layout = layout_.get();
  desc.vertex = vertex.handle();
  desc.position_only = true;
  desc.depth_format = kFormat;
  desc.depth_bias = true;
  pipeline_ = make_graphics_pipeline(device, desc);
  if (alpha_test) {
    const gpu::ShaderModule masked_vertex = gpu::ShaderModule::load(device, "shadow_masked.vert");
    const gpu::ShaderModule masked_fragment = gpu::ShaderModule::load(device, "shadow_masked.frag");
    desc.vertex = masked_vertex.handle();
    desc.fragment = masked_fragment.handle();
    desc.position_only = false;
    masked_pipeline_ = make_graphics_pipeline(device, desc);
  }

  // The image is sampled every frame, shadowed or not: it starts out readable.
  runner.run([&](VkCommandBuffer cmd) {
    gpu::image_barrier(cmd, image_, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                       VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                       VK_ACCESS_SHADER_READ_BIT);
  });
}

void ShadowMaps::record(VkCommandBuffer cmd, const scene::Scene& scene, const GpuMeshes& meshes,
                        const MaterialTextures& materials, VkDescriptorSet frame_set,
                        std::uint32_t layers) {
  passes_ = 0;
  if (layers == 0) return;
  if (layers > capacity())
    throw gpu::GpuError("frame needs " + std::to_string(layers) + " shadow layers, the renderer has " +
                        std::to_string(capacity()));
  // The previous frame's forward pass read the maps; now they are written again.
  gpu::image_barrier(cmd, image_, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                     VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                     VK_ACCESS_SHADER_READ_BIT,
                     VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
                     VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_.get(), 0, 1, &frame_set, 0, nullptr);
  meshes.bind(cmd);
  // Both faces cast: single-sided walls (a Cornell box) must block light from either side.
  vkCmdSetCullMode(cmd, VK_CULL_MODE_NONE);
  vkCmdSetFrontFace(cmd, VK_FRONT_FACE_COUNTER_CLOCKWISE);
  // MASK and BLEND casters go through the alpha-tested pipeline (shadow_masked.frag).
  auto masked = [&](const scene::Instance& inst) {
    const scene::AlphaMode mode = scene.material_of(scene.meshes[static_cast<std::size_t>(inst.mesh)]).alpha_mode;
    return masked_pipeline_ && mode != scene::AlphaMode::Opaque;
  };
  for (std::uint32_t layer = 0; layer < layers; ++layer) {
    VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depth.imageView = layer_views_[layer].get();
    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    depth.clearValue.depthStencil = {1.0f, 0};
    VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
    info.renderArea = {{0, 0}, {map_size_, map_size_}};
    info.layerCount = 1;
    info.pDepthAttachment = &depth;
    vkCmdBeginRendering(cmd, &info);
    set_viewport(cmd, map_size_, map_size_);
    // Opaque casters first with the depth-only pipeline, then masked and blended ones with theirs.
    for (int pass = 0; pass < 2; ++pass) {
      const bool masked_pass = pass == 1;
      if (masked_pass && !masked_pipeline_) break;
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS,
                        masked_pass ? masked_pipeline_.get() : pipeline_.get());
      for (const scene::Instance& inst : scene.instances) {
        if (inst.mesh < 0 || static_cast<std::size_t>(inst.mesh) >= meshes.mesh_count()) continue;
        if (masked(inst) != masked_pass) continue;
        if (masked_pass) {
          const scene::Mesh& mesh = scene.meshes[static_cast<std::size_t>(inst.mesh)];
          // The path tracer sees through a single-sided blended surface from behind, shadow rays
          // too: a shadow ray leaves the receiver towards the light, so it meets the back of a
          // caster whose front faces the light. Such faces are culled here to match. The light
          // projections keep NDC y up (glm's), unlike the cameras' (scene/view.h), so a
          // counter-clockwise front face lands clockwise in the map; a mirroring transform flips
          // it back (glTF).
          const scene::Material& m = scene.material_of(mesh);
          const bool mirrored = glm::determinant(glm::mat3(inst.transform)) < 0.0f;
          vkCmdSetFrontFace(cmd, mirrored ? VK_FRONT_FACE_COUNTER_CLOCKWISE : VK_FRONT_FACE_CLOCKWISE);
          vkCmdSetCullMode(cmd, m.alpha_mode == scene::AlphaMode::Blend && !m.double_sided ? VK_CULL_MODE_FRONT_BIT
                                                                                           : VK_CULL_MODE_NONE);
          const VkDescriptorSet set = materials.set(mesh.material);
          vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_.get(), 1, 1, &set, 0, nullptr);
        }
        const DrawConstants pc = draw_constants(inst.transform, layer, 0);
        vkCmdPushConstants(cmd, layout_.get(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT,
                           0, sizeof(pc), &pc);
        meshes.draw(cmd, inst.mesh);
      }
    }
    vkCmdEndRendering(cmd);
    ++passes_;
  }
  gpu::image_barrier(cmd, image_, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
                     VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                     VK_ACCESS_SHADER_READ_BIT);
}

}  // namespace ddish::raster
