#include "raster/forward_pass.h"

#include <algorithm>
#include <string>
#include <utility>

#include "gpu/device.h"
#include "gpu/driver_quirks.h"
#include "gpu/error.h"
#include "raster/gpu_meshes.h"
#include "raster/gpu_types.h"
#include "raster/material_textures.h"
#include "raster/render_target.h"
#include "scene/scene.h"

namespace ddish::raster {

namespace {

void check_desc(const gpu::Device& device, const ForwardPassDesc& desc) {
  if (desc.sh_order < 1 || desc.sh_order > 4)
    throw gpu::GpuError("the forward pass has SH orders 1..4, not " + std::to_string(desc.sh_order));
  if (desc.sample_shading && !device.features().sample_rate_shading)
    throw gpu::GpuError(device.info().name +
                        " lacks the sampleRateShading feature that sample shading needs");
  if (desc.depth_prepass && !device.features().post_depth_coverage)
    throw gpu::GpuError(device.info().name +
                        " lacks VK_EXT_post_depth_coverage that the depth prepass needs");
}

const gpu::Device& checked(const gpu::Device& device, const ForwardPassDesc& desc) {
  check_desc(device, desc);
  return device;
}

// The trivial shader declares none of the variant's specialization constants; Vulkan ignores
// map entries a shader does not use, so the pipeline is otherwise built exactly as for full.
std::string fragment_shader(const ForwardPassDesc& desc) {
  if (desc.shading == Shading::trivial) return "forward_trivial.frag";
  return "forward_sh" + std::to_string(desc.sh_order) + (desc.depth_prepass ? "_prepassed" : "") + ".frag";
}

// The transparent instances back to front as seen from `eye`: by the distance to the centre of
// each instance's world-space bounds (per instance and primitive, not per triangle: the
// triangles of one mesh blend in index order).
void sort_back_to_front(const scene::Scene& scene, const glm::vec3& eye,
                        std::vector<std::size_t>& instances) {
  std::vector<std::pair<float, std::size_t>> keyed;
  keyed.reserve(instances.size());
  for (std::size_t i : instances) {
    const scene::Instance& inst = scene.instances[i];
    const scene::Mesh& mesh = scene.meshes[static_cast<std::size_t>(inst.mesh)];
    const glm::vec3 c = glm::vec3(inst.transform * glm::vec4(mesh.bounds.center(), 1.0f));
    const glm::vec3 d = c - eye;
    keyed.emplace_back(glm::dot(d, d), i);
  }
  std::stable_sort(keyed.begin(), keyed.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  for (std::size_t k = 0; k < keyed.size(); ++k) instances[k] = keyed[k].second;
}

}  // namespace

ForwardPass::ForwardPass(const gpu::Device& device, const ForwardPassDesc& desc)
    : device_(checked(device, desc)),
      desc_(desc),
      vertex_(gpu::ShaderModule::load(device, "forward.vert")),
      fragment_(gpu::ShaderModule::load(device, fragment_shader(desc))) {
  layout_ = make_pipeline_layout(device, desc.set_layouts, sizeof(DrawConstants));
  if (device.features().multiview)
    max_multiview_ = std::max(1u, device.info().max_multiview_view_count);
  layered_supported_ = device.features().shader_output_layer;
  reset_view_mask_ = gpu::multiview_defect(device.info()) == gpu::MultiviewDefect::timestamps_after_pass_overrun;
  if (desc.depth_prepass && desc.shading == Shading::full)
    depth_masked_.emplace(gpu::ShaderModule::load(device, "forward_depth_masked.frag"));
  pipeline_for(ViewMethod::per_view, 1);
}

void ForwardPass::prepare(ViewMethod method) {
  const std::uint32_t count = method == ViewMethod::multiview ? max_multiview_ : 1u;
  pipeline_for(method, count);
  if (depth_masked_) {
    pipeline_for(method, count, kDepth);
    pipeline_for(method, count, kDepthMasked);
  }
}

VkPipeline ForwardPass::pipeline_for(ViewMethod method, std::uint32_t view_count, Kind kind) {
  if (method == ViewMethod::per_view && pipeline_[kind]) return pipeline_[kind].get();
  if (method == ViewMethod::layered && layered_pipeline_[kind]) return layered_pipeline_[kind].get();
  const std::uint32_t mask = method == ViewMethod::multiview ? (1u << view_count) - 1u : 0u;
  if (method == ViewMethod::multiview) {
    auto it = multiview_pipelines_.find({mask, kind});
    if (it != multiview_pipelines_.end()) return it->second.get();
  }
  if (method == ViewMethod::layered && !layered_vertex_) {
    if (!layered_supported_)
      throw gpu::GpuError(device_.info().name +
                          " lacks the shaderOutputLayer feature that layered view recording needs");
    layered_vertex_.emplace(gpu::ShaderModule::load(device_, "forward_layered.vert"));
  }
  GraphicsPipelineDesc p;
  p.layout = layout_.get();
  p.vertex = method == ViewMethod::layered ? layered_vertex_->handle() : vertex_.handle();
  // The opaque prepass has no fragment stage; the masked one only discards.
  p.fragment = kind == kDepth ? VK_NULL_HANDLE
               : kind == kDepthMasked ? depth_masked_->handle()
                                      : fragment_.handle();
  p.fragment_constants = desc_.variant.constants();
  p.color_format = RenderTarget::kColorFormat;
  p.depth_format = RenderTarget::kDepthFormat;
  p.samples = static_cast<VkSampleCountFlagBits>(desc_.samples);
  p.sample_shading = desc_.sample_shading;
  p.view_mask = mask;
  p.alpha_blend = kind == kBlend;
  // After a prepass the shading finds the depth made and leaves it.
  p.depth_write = !desc_.depth_prepass || kind == kDepth || kind == kDepthMasked;
  p.color_write = kind != kDepth && kind != kDepthMasked;
  Pipeline made = make_graphics_pipeline(device_, p);
  const VkPipeline handle = made.get();
  if (method == ViewMethod::multiview)
    multiview_pipelines_.emplace(std::make_pair(mask, int(kind)), std::move(made));
  else if (method == ViewMethod::layered) layered_pipeline_[kind] = std::move(made);
  else pipeline_[kind] = std::move(made);
  return handle;
}

void ForwardPass::begin_pass(VkCommandBuffer cmd, const RenderTarget& target, VkImageView color_view,
                             VkImageView depth_view, std::uint32_t layers, std::uint32_t view_mask,
                             const std::optional<glm::vec4>& clear, VkPipeline pipeline,
                             std::span<const VkDescriptorSet> sets) const {
  const VkAttachmentLoadOp load = clear ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
  VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  color.imageView = color_view;
  color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  // The clear colour is the environment: no full-screen draw (see the header).
  color.loadOp = load;
  if (clear) color.clearValue.color = {{clear->r, clear->g, clear->b, clear->a}};
  // Multisampled targets are resolved after all views by RenderTarget::end_frame.
  color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  depth.imageView = depth_view;
  depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
  depth.loadOp = load;
  depth.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  depth.clearValue.depthStencil = {1.0f, 0};
  VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
  const std::uint32_t w = target.desc().width, h = target.desc().height;
  info.renderArea = {{0, 0}, {w, h}};
  info.layerCount = layers;  // ignored by multiview passes, which have the view mask instead
  info.viewMask = view_mask;
  info.colorAttachmentCount = 1;
  info.pColorAttachments = &color;
  info.pDepthAttachment = &depth;
  vkCmdBeginRendering(cmd, &info);
  set_viewport(cmd, w, h);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_.get(), 0,
                          static_cast<std::uint32_t>(sets.size()), sets.data(), 0, nullptr);
}

void ForwardPass::record_view_mask_reset(VkCommandBuffer cmd, const RenderTarget& target) const {
  // Loads and stores layer 0 unchanged: nothing is drawn, only the driver's state is reset.
  VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  color.imageView = target.color_view(0);
  color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  color.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
  color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
  info.renderArea = {{0, 0}, {target.desc().width, target.desc().height}};
  info.layerCount = 1;
  info.colorAttachmentCount = 1;
  info.pColorAttachments = &color;
  vkCmdBeginRendering(cmd, &info);
  vkCmdEndRendering(cmd);
}

void ForwardPass::draw_items(VkCommandBuffer cmd, const scene::Scene& scene,
                             const MaterialTextures& materials, std::span<const DrawItem> items,
                             std::uint32_t view_index, std::uint32_t first_instance,
                             std::array<VkPipeline, 2> depth) const {
  int bound_material = -2;  // no material index is -2
  std::uint32_t pushed_instance = ~0u;
  VkPipeline bound_pipeline = VK_NULL_HANDLE;
  for (const DrawItem& item : items) {
    const scene::Instance& inst = scene.instances[item.instance];
    const scene::Mesh& mesh = scene.meshes[static_cast<std::size_t>(inst.mesh)];
    if (mesh.material != bound_material) {
      bound_material = mesh.material;
      if (depth[0] != VK_NULL_HANDLE) {
        const bool masked = scene.material_of(mesh).alpha_mode == scene::AlphaMode::Mask;
        const VkPipeline pipeline = depth[masked ? 1 : 0];
        if (pipeline != bound_pipeline) {
          vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
          bound_pipeline = pipeline;
        }
      }
      const VkDescriptorSet set = materials.set(mesh.material);
      vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_.get(), kMaterialSet, 1,
                              &set, 0, nullptr);
      vkCmdSetCullMode(cmd, scene.material_of(mesh).double_sided ? VK_CULL_MODE_NONE
                                                                 : VK_CULL_MODE_BACK_BIT);
    }
    // One instance's clusters follow one another: its constants are pushed once for all.
    if (item.instance != pushed_instance) {
      pushed_instance = item.instance;
      // glTF: a mirroring transform turns clockwise triangles into front faces.
      const bool mirrored = glm::determinant(glm::mat3(inst.transform)) < 0.0f;
      vkCmdSetFrontFace(cmd, mirrored ? VK_FRONT_FACE_CLOCKWISE : VK_FRONT_FACE_COUNTER_CLOCKWISE);
      const DrawConstants pc =
          draw_constants(inst.transform, view_index, static_cast<std::uint32_t>(mesh.material + 1));
      vkCmdPushConstants(cmd, layout_.get(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT,
                         0, sizeof(pc), &pc);
    }
    vkCmdDrawIndexed(cmd, item.index_count, 1, item.first_index, item.vertex_offset, first_instance);
  }
}

void ForwardPass::draw_opaque(VkCommandBuffer cmd, const scene::Scene& scene,
                              const MaterialTextures& materials, ViewMethod method,
                              std::uint32_t view_count, std::uint32_t view_index,
                              std::uint32_t first_instance) {
  if (depth_masked_) {
    draw_items(cmd, scene, materials, items_, view_index, first_instance,
               {pipeline_for(method, view_count, kDepth), pipeline_for(method, view_count, kDepthMasked)});
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_for(method, view_count));
  }
  draw_items(cmd, scene, materials, items_, view_index, first_instance);
}

void ForwardPass::record(VkCommandBuffer cmd, const scene::Scene& scene, const GpuMeshes& meshes,
                         const MaterialTextures& materials, std::array<VkDescriptorSet, 3> sets,
                         const RenderTarget& target, const ForwardViews& views,
                         const glm::vec4& clear) {
  passes_ = 0;
  stats_ = {};
  const auto n = static_cast<std::uint32_t>(views.view_proj.size());
  const std::vector<std::size_t> order = instances_by_material(scene, meshes, false);
  const std::vector<std::size_t> blended = instances_by_material(scene, meshes, true);
  auto pass_views = [&](std::uint32_t first, std::uint32_t count) {
    return PassViews{views.view_proj.subspan(first, count), views.eyes.subspan(first, count)};
  };
  // The transparent pass of views [first, first + count), after their opaque draws: BLEND
  // instances back to front from the first view's eye (a multiview block's views sit close
  // together), drawn with the blending pipeline in the same rendering pass.
  auto record_blended = [&](std::uint32_t first, std::uint32_t count, VkPipeline pipeline,
                            std::uint32_t view_index, std::uint32_t first_instance) {
    if (blended.empty()) return;
    std::vector<std::size_t> sorted = blended;
    sort_back_to_front(scene, views.eyes[first], sorted);
    blend_items_.clear();
    build_draws(scene, meshes, sorted, pass_views(first, count), views.cull, blend_items_, stats_);
    if (blend_items_.empty()) return;
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
    draw_items(cmd, scene, materials, blend_items_, view_index, first_instance);
  };

  switch (views.method) {
    case ViewMethod::per_view:
      for (std::uint32_t v = 0; v < n; ++v) {
        items_.clear();
        build_draws(scene, meshes, order, pass_views(v, 1), views.cull, items_, stats_);
        begin_pass(cmd, target, target.color_view(v), target.depth_view(v), 1, 0, clear,
                   pipeline_for(ViewMethod::per_view, 1), sets);
        meshes.bind(cmd);
        draw_opaque(cmd, scene, materials, ViewMethod::per_view, 1, v, 0);
        record_blended(v, 1, blended.empty() ? VK_NULL_HANDLE : pipeline_for(ViewMethod::per_view, 1, kBlend),
                       v, 0);
        vkCmdEndRendering(cmd);
        ++passes_;
      }
      break;
    case ViewMethod::multiview:
      // A target without view blocks gets one-view multiview passes (still correct).
      for (std::uint32_t b = 0, first = 0; first < n; ++b) {
        const bool blocks = target.block_count() > 0;
        // A frame's last batch may fill only part of the target's last block.
        const std::uint32_t count = blocks ? std::min(target.block_layers(b), n - first) : 1u;
        items_.clear();
        build_draws(scene, meshes, order, pass_views(first, count), views.cull, items_, stats_);
        begin_pass(cmd, target, blocks ? target.color_block_view(b) : target.color_view(first),
                   blocks ? target.depth_block_view(b) : target.depth_view(first), 1, (1u << count) - 1u,
                   clear, pipeline_for(ViewMethod::multiview, count), sets);
        meshes.bind(cmd);
        draw_opaque(cmd, scene, materials, ViewMethod::multiview, count, first, 0);
        record_blended(first, count,
                       blended.empty() ? VK_NULL_HANDLE : pipeline_for(ViewMethod::multiview, count, kBlend),
                       first, 0);
        vkCmdEndRendering(cmd);
        ++passes_;
        first += count;
      }
      if (reset_view_mask_) record_view_mask_reset(cmd, target);
      break;
    case ViewMethod::layered: {
      const VkPipeline pipeline = pipeline_for(ViewMethod::layered, n);
      begin_pass(cmd, target, target.color_all_view(), target.depth_all_view(), n, 0, clear,
                 pipeline, sets);
      meshes.bind(cmd);
      // Each view's own draws, its index as the instance (the shader's layer and view).
      for (std::uint32_t v = 0; v < n; ++v) {
        items_.clear();
        build_draws(scene, meshes, order, pass_views(v, 1), views.cull, items_, stats_);
        draw_opaque(cmd, scene, materials, ViewMethod::layered, n, 0, v);
      }
      // Then each view's transparent draws, sorted from its own eye (layers are independent).
      if (!blended.empty()) {
        const VkPipeline blend_pipeline = pipeline_for(ViewMethod::layered, n, kBlend);
        for (std::uint32_t v = 0; v < n; ++v) record_blended(v, 1, blend_pipeline, 0, v);
      }
      vkCmdEndRendering(cmd);
      ++passes_;
      break;
    }
  }
}

void ForwardPass::record_transparent(VkCommandBuffer cmd, const scene::Scene& scene,
                                     const GpuMeshes& meshes, const MaterialTextures& materials,
                                     std::array<VkDescriptorSet, 3> sets, const RenderTarget& target,
                                     const ForwardViews& views) {
  passes_ = 0;
  stats_ = {};
  const std::vector<std::size_t> blended = instances_by_material(scene, meshes, true);
  if (blended.empty()) return;
  const VkPipeline pipeline = pipeline_for(ViewMethod::per_view, 1, kBlend);
  for (std::uint32_t v = 0; v < views.view_proj.size(); ++v) {
    std::vector<std::size_t> sorted = blended;
    sort_back_to_front(scene, views.eyes[v], sorted);
    blend_items_.clear();
    build_draws(scene, meshes, sorted, PassViews{views.view_proj.subspan(v, 1), views.eyes.subspan(v, 1)},
                views.cull, blend_items_, stats_);
    if (blend_items_.empty()) continue;
    begin_pass(cmd, target, target.color_view(v), target.depth_view(v), 1, 0, std::nullopt, pipeline, sets);
    meshes.bind(cmd);
    draw_items(cmd, scene, materials, blend_items_, v, 0);
    vkCmdEndRendering(cmd);
    ++passes_;
  }
}

}  // namespace ddish::raster
