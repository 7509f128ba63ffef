#include "raster/forward_pass.h"

#include <algorithm>
#include <numeric>
#include <string>

#include "gpu/device.h"
#include "gpu/error.h"
#include "gpu/shader.h"
#include "raster/gpu_meshes.h"
#include "raster/gpu_types.h"
#include "raster/material_textures.h"
#include "raster/render_target.h"
#include "scene/scene.h"

namespace ddish::raster {

ForwardPass::ForwardPass(const gpu::Device& device, const ForwardPassDesc& desc) : desc_(desc) {
  if (desc.sh_order < 1 || desc.sh_order > 4)
    throw gpu::GpuError("the forward pass has SH orders 1..4, not " + std::to_string(desc.sh_order));
  if (desc.sample_shading && !device.features().sample_rate_shading)
    throw gpu::GpuError(device.info().name +
                        " lacks the sampleRateShading feature that sample shading needs");
  layout_ = make_pipeline_layout(device, desc.set_layouts, sizeof(DrawConstants));
  const gpu::ShaderModule vertex = gpu::ShaderModule::load(device, "forward.vert");
  const gpu::ShaderModule fragment =
      gpu::ShaderModule::load(device, "forward_sh" + std::to_string(desc.sh_order) + ".frag");
  GraphicsPipelineDesc p;
  p.layout = layout_.get();
  p.vertex = vertex.handle();
  p.fragment = fragment.handle();
  p.fragment_constants = desc.variant.constants();
  p.color_format = RenderTarget::kColorFormat;
  p.depth_format = RenderTarget::kDepthFormat;
  p.samples = static_cast<VkSampleCountFlagBits>(desc.samples);
  p.sample_shading = desc.sample_shading;
  pipeline_ = make_graphics_pipeline(device, p);
}

void ForwardPass::record(VkCommandBuffer cmd, const scene::Scene& scene, const GpuMeshes& meshes,
                         const MaterialTextures& materials, std::array<VkDescriptorSet, 3> sets,
                         const RenderTarget& target, std::uint32_t views, const glm::vec3& environment) {
  passes_ = 0;
  // Instances by material, so that each material's set is bound once per view.
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < scene.instances.size(); ++i) {
    const int mesh = scene.instances[i].mesh;
    if (mesh >= 0 && static_cast<std::size_t>(mesh) < meshes.mesh_count()) order.push_back(i);
  }
  auto material_of = [&](std::size_t i) {
    return scene.meshes[static_cast<std::size_t>(scene.instances[i].mesh)].material;
  };
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return material_of(a) < material_of(b); });

  const std::uint32_t w = target.desc().width, h = target.desc().height;
  for (std::uint32_t view = 0; view < views; ++view) {
    VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    color.imageView = target.color_view(view);
    color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    color.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    color.clearValue.color = {{environment.r, environment.g, environment.b, 1.0f}};
    // Multisampled targets are resolved after all views by RenderTarget::end_frame.
    color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depth.imageView = target.depth_view(view);
    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    depth.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    depth.clearValue.depthStencil = {1.0f, 0};
    VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
    info.renderArea = {{0, 0}, {w, h}};
    info.layerCount = 1;
    info.colorAttachmentCount = 1;
    info.pColorAttachments = &color;
    info.pDepthAttachment = &depth;
    vkCmdBeginRendering(cmd, &info);
    set_viewport(cmd, w, h);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_.get());
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_.get(), 0,
                            static_cast<std::uint32_t>(sets.size()), sets.data(), 0, nullptr);
    meshes.bind(cmd);
    int bound_material = -2;  // no material index is -2
    for (std::size_t i : order) {
      const scene::Instance& inst = scene.instances[i];
      const scene::Mesh& mesh = scene.meshes[static_cast<std::size_t>(inst.mesh)];
      if (mesh.material != bound_material) {
        bound_material = mesh.material;
        const VkDescriptorSet set = materials.set(mesh.material);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_.get(), kMaterialSet,
                                1, &set, 0, nullptr);
        vkCmdSetCullMode(cmd, scene.material_of(mesh).double_sided ? VK_CULL_MODE_NONE
                                                                   : VK_CULL_MODE_BACK_BIT);
      }
      // glTF: a mirroring transform turns clockwise triangles into front faces.
      const bool mirrored = glm::determinant(glm::mat3(inst.transform)) < 0.0f;
      vkCmdSetFrontFace(cmd, mirrored ? VK_FRONT_FACE_CLOCKWISE : VK_FRONT_FACE_COUNTER_CLOCKWISE);
      const DrawConstants pc = draw_constants(inst.transform, view,
                                              static_cast<std::uint32_t>(mesh.material + 1));
      vkCmdPushConstants(cmd, layout_.get(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT,
                         0, sizeof(pc), &pc);
      meshes.draw(cmd, inst.mesh);
    }
    vkCmdEndRendering(cmd);
    ++passes_;
  }
}

}  // namespace ddish::raster
