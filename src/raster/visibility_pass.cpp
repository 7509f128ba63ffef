#include "raster/visibility_pass.h"

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <string>

#include "gpu/commands.h"
#include "gpu/device.h"
#include "gpu/error.h"
#include "raster/gpu_meshes.h"
#include "raster/gpu_types.h"
#include "raster/material_textures.h"
#include "raster/render_target.h"
#include "scene/scene.h"

namespace ddish::raster {

namespace {

// One scene instance as visibility_shade.glsl reads it (its Instance struct, std430).
struct InstanceData {
  glm::mat4 model{1.0f};
  glm::vec4 normal_matrix[3]{};
  glm::uvec4 info{0u};  // material (MaterialTextures' set order), vertex offset, mirrored
};
static_assert(sizeof(InstanceData) == 128);

// Specialization constants of the shading after the variant's 0..5 (visibility_shade.glsl).
constexpr std::uint32_t kSlotImagesConstant = 10;
constexpr std::uint32_t kMaterialStrideConstant = 11;
constexpr std::uint32_t kSamplesConstant = 12;

const gpu::Device& checked(const gpu::Device& device, const VisibilityPassDesc& desc,
                           const MaterialTextures& materials) {
  if (desc.sh_order < 1 || desc.sh_order > 4)
    throw gpu::GpuError("the visibility pass has SH orders 1..4, not " + std::to_string(desc.sh_order));
  if (const auto why = VisibilityPass::unsupported(device, materials)) throw gpu::GpuError(*why);
  return device;
}

std::string shade_shader(const VisibilityPassDesc& desc) {
  return "visibility_shade_sh" + std::to_string(desc.sh_order) + (desc.samples > 1 ? "_ms" : "") + ".frag";
}

// Every layer of `image` as a 2D array view, even of one layer (gpu::Image::make_view gives a
// plain 2D view then, which the shading's array sampler cannot read).
gpu::ImageView array_view(VkDevice device, const gpu::Image& image) {
  VkImageViewCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  info.image = image.handle();
  info.viewType = VK_IMAGE_VIEW_TYPE_2D_ARRAY;
  info.format = image.desc().format;
  info.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, image.desc().layers};
  VkImageView view = VK_NULL_HANDLE;
  gpu::check(vkCreateImageView(device, &info, nullptr, &view), "vkCreateImageView");
  return gpu::ImageView(device, view);
}

// Integer images take no linear filter; the shading reads them with texelFetch anyway.
Sampler make_nearest_sampler(VkDevice device) {
  VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  info.magFilter = VK_FILTER_NEAREST;
  info.minFilter = VK_FILTER_NEAREST;
  info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  info.addressModeU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  info.addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  VkSampler sampler = VK_NULL_HANDLE;
  gpu::check(vkCreateSampler(device, &info, nullptr, &sampler), "vkCreateSampler");
  return Sampler(device, sampler);
}

OwnedDescriptorSet make_set(const gpu::Device& device, const MaterialTextures& materials) {
  constexpr VkShaderStageFlags fs = VK_SHADER_STAGE_FRAGMENT_BIT;
  const auto slots = static_cast<std::uint32_t>(materials.slot_images().size());
  const std::array<VkDescriptorSetLayoutBinding, 6> bindings{{
      {0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, fs, nullptr},  // ids
      {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, fs, nullptr},          // instances
      {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, fs, nullptr},          // indices
      {3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, fs, nullptr},          // vertices
      {4, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, fs, nullptr},          // materials
      {5, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, slots, fs, nullptr},
  }};
  return OwnedDescriptorSet(device.handle(), bindings);
}

}  // namespace

std::optional<std::string> VisibilityPass::unsupported(const gpu::Device& device,
                                                       const MaterialTextures& materials) {
  if (!device.features().sampled_image_non_uniform_indexing)
    return device.info().name +
           " lacks shaderSampledImageArrayNonUniformIndexing, which the visibility pass's material reads need";
  if (!device.features().geometry_shader)
    return device.info().name + " lacks the geometryShader feature that gl_PrimitiveID in the visibility pass needs";
  // The material reads take one texture at a time for the lanes that share it
  // (visibility_shade.glsl's read_slot): subgroupBroadcastFirst in the fragment stage.
  VkPhysicalDeviceSubgroupProperties subgroup{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
  VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  properties.pNext = &subgroup;
  vkGetPhysicalDeviceProperties2(device.physical(), &properties);
  if (!(subgroup.supportedStages & VK_SHADER_STAGE_FRAGMENT_BIT) ||
      !(subgroup.supportedOperations & VK_SUBGROUP_FEATURE_BALLOT_BIT))
    return device.info().name + " lacks subgroup ballot operations in fragment shaders, which the visibility pass's material reads use";
  const VkPhysicalDeviceLimits& l = device.limits();
  const std::uint64_t images = materials.slot_images().size() + 1;  // + the ids
  const std::uint64_t most = std::min({l.maxPerStageDescriptorSampledImages, l.maxPerStageDescriptorSamplers,
                                       l.maxDescriptorSetSampledImages, l.maxDescriptorSetSamplers});
  if (images > most)
    return "the visibility pass would bind " + std::to_string(images) + " textures, more than the " +
           std::to_string(most) + " " + device.info().name + " allows a shader";
  return std::nullopt;
}

VisibilityPass::VisibilityPass(const gpu::Device& device, const VisibilityPassDesc& desc,
                               const GpuMeshes& meshes, const MaterialTextures& materials)
    : device_(checked(device, desc, materials)),
      desc_(desc),
      vertex_(gpu::ShaderModule::load(device, "visibility.vert")),
      opaque_(gpu::ShaderModule::load(device, "visibility.frag")),
      masked_(gpu::ShaderModule::load(device, "visibility_masked.frag")),
      fullscreen_(gpu::ShaderModule::load(device, "fullscreen.vert")),
      shade_(gpu::ShaderModule::load(device, shade_shader(desc))),
      set_(make_set(device, materials)),
      sampler_(make_nearest_sampler(device.handle())) {
  layered_supported_ = device.features().shader_output_layer;
  geometry_layout_ = make_pipeline_layout(device, desc.set_layouts, sizeof(DrawConstants));
  const std::array<VkDescriptorSetLayout, 4> shade_sets{desc.set_layouts[kFrameSet], desc.set_layouts[kProbeSet],
                                                        desc.set_layouts[kBrdfSet], set_.layout()};
  shade_layout_ = make_pipeline_layout(device, shade_sets, sizeof(DrawConstants));

  GraphicsPipelineDesc p;
  p.layout = shade_layout_.get();
  p.vertex = fullscreen_.handle();
  p.fragment = shade_.handle();
  p.fragment_constants = desc.variant.constants();
  p.fragment_int_constants = {
      {kSlotImagesConstant, static_cast<std::uint32_t>(materials.slot_images().size())},
      {kMaterialStrideConstant, static_cast<std::uint32_t>(materials.uniform_stride() / sizeof(glm::vec4))},
      {kSamplesConstant, desc.samples}};
  p.color_format = RenderTarget::kColorFormat;
  p.samples = static_cast<VkSampleCountFlagBits>(desc.shade_resolved ? 1u : desc.samples);
  p.fullscreen = true;
  p.depth_write = false;
  shade_pipeline_ = make_graphics_pipeline(device, p);

  // One instance for now; record() grows it to the scene's instances.
  instances_ = gpu::Buffer(device, sizeof(InstanceData), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                           gpu::MemoryUse::upload);
  set_.write_storage_buffer(2, meshes.index_buffer().descriptor());
  set_.write_storage_buffer(3, meshes.vertex_buffer().descriptor());
  set_.write_storage_buffer(4, materials.uniforms().descriptor());
  set_.write_images(5, materials.slot_images());
  geometry_pipeline(false, false);
}

void VisibilityPass::prepare(ViewMethod method) {
  const bool layered = method == ViewMethod::layered;
  geometry_pipeline(layered, false);
  geometry_pipeline(layered, true);
}

VkPipeline VisibilityPass::geometry_pipeline(bool layered, bool masked) {
  Pipeline& made = geometry_[layered][masked];
  if (made) return made.get();
  if (layered && !layered_vertex_) {
    if (!layered_supported_)
      throw gpu::GpuError(device_.info().name +
                          " lacks the shaderOutputLayer feature that layered view recording needs");
    layered_vertex_.emplace(gpu::ShaderModule::load(device_, "visibility_layered.vert"));
  }
  GraphicsPipelineDesc p;
  p.layout = geometry_layout_.get();
  p.vertex = layered ? layered_vertex_->handle() : vertex_.handle();
  p.fragment = masked ? masked_.handle() : opaque_.handle();
  p.fragment_constants = desc_.variant.constants();
  p.color_format = kIdFormat;
  p.depth_format = RenderTarget::kDepthFormat;
  p.samples = static_cast<VkSampleCountFlagBits>(desc_.samples);
  made = make_graphics_pipeline(device_, p);
  return made.get();
}

void VisibilityPass::ensure_ids(const RenderTarget& target) {
  const RenderTargetDesc& t = target.desc();
  if (ids_.handle() != VK_NULL_HANDLE && ids_.desc().width == t.width && ids_.desc().height == t.height &&
      ids_.desc().layers == t.layers)
    return;
  id_layers_.clear();
  id_all_ = {};
  ids_ = gpu::Image(device_, {.width = t.width, .height = t.height, .layers = t.layers, .format = kIdFormat,
                              .usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
                              .samples = static_cast<VkSampleCountFlagBits>(t.samples)});
  for (std::uint32_t l = 0; l < t.layers; ++l) id_layers_.push_back(ids_.make_view(l, 1));
  id_all_ = array_view(device_.handle(), ids_);
  const VkDescriptorImageInfo info{sampler_.get(), id_all_.get(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  set_.write_images(0, {&info, 1});
}

void VisibilityPass::write_instances(const scene::Scene& scene, const GpuMeshes& meshes,
                                     const MaterialTextures& materials) {
  if (instances_.size() < sizeof(InstanceData) * scene.instances.size())
    instances_ = gpu::Buffer(device_, sizeof(InstanceData) * scene.instances.size(),
                             VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUse::upload);
  set_.write_storage_buffer(1, instances_.descriptor());
  std::vector<InstanceData> data(scene.instances.size());
  const auto default_material = static_cast<std::uint32_t>(materials.material_count() - 1);
  for (std::size_t i = 0; i < scene.instances.size(); ++i) {
    const scene::Instance& inst = scene.instances[i];
    if (inst.mesh < 0 || static_cast<std::size_t>(inst.mesh) >= meshes.mesh_count()) continue;
    const scene::Mesh& mesh = scene.meshes[static_cast<std::size_t>(inst.mesh)];
    const DrawConstants c = draw_constants(inst.transform, 0, 0);
    // MaterialTextures::set's rule: an index outside the scene's materials is the default.
    const bool known = mesh.material >= 0 && static_cast<std::uint32_t>(mesh.material) < default_material;
    data[i].model = c.model;
    for (int k = 0; k < 3; ++k) data[i].normal_matrix[k] = c.normal_matrix[k];
    data[i].info = {known ? static_cast<std::uint32_t>(mesh.material) : default_material,
                    static_cast<std::uint32_t>(meshes.range(inst.mesh).vertex_offset),
                    glm::determinant(glm::mat3(inst.transform)) < 0.0f ? 1u : 0u, 0u};
  }
  if (!data.empty()) instances_.write(data.data(), data.size() * sizeof(InstanceData));
}

void VisibilityPass::begin_geometry(VkCommandBuffer cmd, const RenderTarget& target, VkImageView ids,
                                    VkImageView depth_view, std::uint32_t layers) const {
  VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  color.imageView = ids;
  color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  color.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  color.clearValue.color.uint32[0] = 0xffffffffu;  // kNothing in visibility_shade.glsl
  color.clearValue.color.uint32[1] = 0xffffffffu;
  VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  depth.imageView = depth_view;
  depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
  depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;  // the transparent pass tests against it
  depth.clearValue.depthStencil = {1.0f, 0};
  VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
  const std::uint32_t w = target.desc().width, h = target.desc().height;
  info.renderArea = {{0, 0}, {w, h}};
  info.layerCount = layers;
  info.colorAttachmentCount = 1;
  info.pColorAttachments = &color;
  info.pDepthAttachment = &depth;
  vkCmdBeginRendering(cmd, &info);
  set_viewport(cmd, w, h);
}

void VisibilityPass::draw_geometry(VkCommandBuffer cmd, const scene::Scene& scene,
                                   const MaterialTextures& materials, bool layered,
                                   std::uint32_t view_index, std::uint32_t first_instance) {
  constexpr VkShaderStageFlags stages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
  int bound_material = -2;  // no material index is -2
  std::uint32_t pushed_instance = ~0u;
  VkPipeline bound_pipeline = VK_NULL_HANDLE;
  for (const DrawItem& item : items_) {
    const scene::Instance& inst = scene.instances[item.instance];
    const scene::Mesh& mesh = scene.meshes[static_cast<std::size_t>(inst.mesh)];
    if (mesh.material != bound_material) {
      bound_material = mesh.material;
      const scene::Material& material = scene.material_of(mesh);
      const bool masked = material.alpha_mode == scene::AlphaMode::Mask;
      const VkPipeline pipeline = geometry_pipeline(layered, masked);
      if (pipeline != bound_pipeline) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
        bound_pipeline = pipeline;
      }
      // Only the masked fragment stage reads the material (its base colour's alpha).
      if (masked) {
        const VkDescriptorSet set = materials.set(mesh.material);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, geometry_layout_.get(), kMaterialSet, 1,
                                &set, 0, nullptr);
      }
      vkCmdSetCullMode(cmd, material.double_sided ? VK_CULL_MODE_NONE : VK_CULL_MODE_BACK_BIT);
    }
    if (item.instance != pushed_instance) {
      pushed_instance = item.instance;
      // glTF: a mirroring transform turns clockwise triangles into front faces.
      const bool mirrored = glm::determinant(glm::mat3(inst.transform)) < 0.0f;
      vkCmdSetFrontFace(cmd, mirrored ? VK_FRONT_FACE_CLOCKWISE : VK_FRONT_FACE_COUNTER_CLOCKWISE);
      DrawConstants pc = draw_constants(inst.transform, view_index, static_cast<std::uint32_t>(mesh.material + 1));
      pc.instance = item.instance;
      vkCmdPushConstants(cmd, geometry_layout_.get(), stages, 0, sizeof(pc), &pc);
    }
    // gl_PrimitiveID counts from the draw's first index.
    const std::uint32_t first_triangle = item.first_index / 3;
    vkCmdPushConstants(cmd, geometry_layout_.get(), stages, offsetof(DrawConstants, first_triangle),
                       sizeof(first_triangle), &first_triangle);
    vkCmdDrawIndexed(cmd, item.index_count, 1, item.first_index, item.vertex_offset, first_instance);
  }
}

void VisibilityPass::record(VkCommandBuffer cmd, const scene::Scene& scene, const GpuMeshes& meshes,
                            const MaterialTextures& materials, std::array<VkDescriptorSet, 3> sets,
                            const RenderTarget& target, const ForwardViews& views, const glm::vec4& clear) {
  if (target.desc().samples != desc_.samples || (target.multisampled() && target.resolves() == desc_.shade_resolved))
    throw std::logic_error("VisibilityPass::record: the target's samples or colour are not the pass's");
  passes_ = 0;
  stats_ = {};
  ensure_ids(target);
  write_instances(scene, meshes, materials);
  const auto n = static_cast<std::uint32_t>(views.view_proj.size());
  order_ = instances_by_material(scene, meshes, false);
  auto one_view = [&](std::uint32_t v) {
    return PassViews{views.view_proj.subspan(v, 1), views.eyes.subspan(v, 1)};
  };

  // The ids of the last frame are discarded; the geometry writes them anew.
  gpu::image_barrier(cmd, ids_, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                     VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, 0, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                     VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT);
  if (views.method == ViewMethod::layered) {
    begin_geometry(cmd, target, id_all_.get(), target.depth_all_view(), n);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, geometry_layout_.get(), 0, 3, sets.data(), 0,
                            nullptr);
    meshes.bind(cmd);
    for (std::uint32_t v = 0; v < n; ++v) {
      items_.clear();
      build_draws(scene, meshes, order_, one_view(v), views.cull, items_, stats_);
      draw_geometry(cmd, scene, materials, true, 0, v);  // the instance is the view
    }
    vkCmdEndRendering(cmd);
    ++passes_;
  } else {
    for (std::uint32_t v = 0; v < n; ++v) {
      items_.clear();
      build_draws(scene, meshes, order_, one_view(v), views.cull, items_, stats_);
      begin_geometry(cmd, target, id_layers_[v].get(), target.depth_view(v), 1);
      vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, geometry_layout_.get(), 0, 3, sets.data(),
                              0, nullptr);
      meshes.bind(cmd);
      draw_geometry(cmd, scene, materials, false, v, 0);
      vkCmdEndRendering(cmd);
      ++passes_;
    }
  }
  gpu::image_barrier(cmd, ids_, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                     VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                     VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);

  // The shading: one full-screen triangle per view, into its colour layer cleared to `clear`.
  const std::array<VkDescriptorSet, 4> shade_sets{sets[0], sets[1], sets[2], set_.set()};
  const std::uint32_t w = target.desc().width, h = target.desc().height;
  for (std::uint32_t v = 0; v < n; ++v) {
    VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    color.imageView = target.color_view(v);
    color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    color.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    color.clearValue.color = {{clear.r, clear.g, clear.b, clear.a}};
    VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
    info.renderArea = {{0, 0}, {w, h}};
    info.layerCount = 1;
    info.colorAttachmentCount = 1;
    info.pColorAttachments = &color;
    vkCmdBeginRendering(cmd, &info);
    set_viewport(cmd, w, h);
    vkCmdSetCullMode(cmd, VK_CULL_MODE_NONE);
    vkCmdSetFrontFace(cmd, VK_FRONT_FACE_COUNTER_CLOCKWISE);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, shade_pipeline_.get());
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, shade_layout_.get(), 0, 4, shade_sets.data(), 0,
                            nullptr);
    DrawConstants pc{};
    pc.model[0] = clear;  // what a sample that sees nothing adds (visibility_shade.glsl)
    pc.view_index = v;
    vkCmdPushConstants(cmd, shade_layout_.get(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                       sizeof(pc), &pc);
    vkCmdDraw(cmd, 3, 1, 0, 0);
    vkCmdEndRendering(cmd);
  }
  // The transparent pass (ForwardPass::record_transparent) blends over this colour and tests
  // against the geometry's depth.
  gpu::memory_barrier(cmd,
                      VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
                      VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                      VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                          VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
                      VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT |
                          VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT);
}

}  // namespace ddish::raster
