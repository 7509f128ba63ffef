// The visibility pass (RendererOptions::shading_pass = visibility, raster/shading_pass.h): the
// opaque and alpha-masked instances of every view are drawn once into depth and an id image
// that holds, per sample, the scene instance and the triangle it sees (visibility.frag;
// masked materials discard as the forward shading does, visibility_masked.frag). Then one
// full-screen triangle per view shades each pixel once (visibility_shade.glsl): it reads the
// triangles of its samples back from the scene's vertex and index buffers, evaluates the
// material (textures picked per pixel from one array, so the device needs non-uniform
// sampled-image indexing, and subgroup ballot for read_slot's loop) and lights it exactly as
// the forward shader does, and writes the mean over its samples, so the resolve is
// unchanged; where no BLEND material follows, it writes that mean straight into the resolve
// image (VisibilityPassDesc::shade_resolved): no multisampled colour is stored or resolved,
// 8 bytes a sample less and, on lavapipe, about 2.5 ms a 420x560 view at MSAA 4 (the
// resolve; frame minus forward GPU time 4.5-5.3 -> 2.4-2.7 ms on Sponza, bench/raster_views
// --frames 21 --probe-visibility 8). glTF BLEND instances then go through the forward pass's
// transparent pass (ForwardPass::record_transparent) over this depth.
//
// Why: lavapipe shades fragments in 4x4 blocks with a coverage mask, so the forward pass's
// small triangles leave most lanes idle, and every layer of overdraw that survives the early
// depth test is shaded. Here the geometry pass costs about the trivial-shader floor (1.01-1.04x
// of it measured with the shading left out) and the shading runs on full blocks of visible
// pixels. Process CPU of full shading / trivial floor (bench/raster_views --shading-pass both,
// 420x560, MSAA 4, per-view, culling, one run at load 8-9): Sponza 3.03x against the forward
// pass's 3.78x (1 view), 2.43x against 3.19x (4 views); Breakfast room 2.74x against 3.14x,
// 2.67x against 3.14x. Shading only each pixel's first triangle measured 1.9x; the rest was
// (before the per-surface shading below) the further triangles of edge pixels (a third of
// Sponza's pixels at 420x560, MSAA 4).
// Listing the edge pixels in a compute pass and shading their further triangles there with
// full lanes (branch s19-compact-experiment) gave the same images and the same ratios within
// the noise (4 views, load 9-12: Sponza 2.28x and 2.34x against 2.22x and 2.45x, Breakfast
// room 2.61x and 2.44x against 2.69x and 2.72x): there an edge pixel cost about three times a
// pixel's first shading in this pass (lavapipe's compute path, or neighbouring work items
// from unrelated triangles and materials), so the lanes it saved were spent. A fragment pass over
// a compact image (16 edge pixels to a full 4x4 block) instead did no better either. Of the
// terms, before the per-surface shading, the material textures cost most: without
// them 2.2x against 3.2x, without direct lights 2.9x, without probe light 3.0x, without
// shadows or specular probes 3.2x (one view, load 9-10). The forward pass, whose textures
// are bound per draw, pays less for them (2.9-3.1x without against 3.7x), so the material
// reads take one texture at a time for the lanes that share it (visibility_shade.glsl's
// read_slot): the same pixels, 3.01x against 3.20x (Sponza, 1 view, mean of five interleaved
// runs at load 6-7). textureLod instead of textureGrad changed nothing measurable. A pixel's
// triangles that continue one surface (the same instance seen from the same side, a vertex
// index in common: visibility_shade.glsl's continues()) share one shading; the geometry pass
// marks back-facing samples in the id so the test reads six indices and no vertex. Frame ms of
// full shading / trivial floor, interleaved pairs (bench/raster_views --views 1 --size 420x560
// --frames 3 --shading both --shading-pass visibility, quiet machine): Sponza 3.03x and 3.02x
// before, 2.49x and 2.49x after; Breakfast room 2.91x and 2.87x before, 2.41x and 2.48x after.
// The images against the 512-spp references (160x120, 4 frames): Sponza 22.567 -> 22.550 dB,
// Breakfast room 23.833 -> 23.830 dB; Sponza's 420x560 image moves by 47.5 dB. A first version
// that also read the six vertices to reject folds over 60 degrees and opposite facings gained
// half as much (2.76-2.80x on Sponza) for no better image; merging every triangle of an
// instance would be about 2.35x, but the vertex rule keeps colour and UV seams apart. Where
// Sponza's time goes now (1 view, frame ms, one run each): trivial floor 60-65; the visibility
// pass with a constant shading 78 (the ids' writes and the full-screen pass's fixed cost);
// with the ids read and merged 82; with the material and its textures but no light 122;
// without textures but with light 133; full 151. So the light is about 29 ms, the material's
// reconstruction 22 and its textures 18.
// (An earlier try at merging, which compared positions and normals, cost about what it saved.)
//
// Recording: per-view and layered as ViewMethod says; multiview draws the geometry per view
// (lavapipe's multiview is not trustworthy, raster/view_method.h, and the shading is per view
// anyway). The target's depth is stored (the transparent pass tests against it).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <glm/glm.hpp>
#include <vulkan/vulkan.h>

#include "gpu/buffer.h"
#include "gpu/image.h"
#include "gpu/shader.h"
#include "raster/draw_list.h"
#include "raster/forward_pass.h"
#include "raster/graphics_pipeline.h"
#include "raster/probe_descriptor_set.h"
#include "raster/shader_variant.h"
#include "raster/view_method.h"

namespace ddish::gpu {
class Device;
}

namespace ddish::scene {
struct Scene;
}

namespace ddish::raster {

class GpuMeshes;
class MaterialTextures;
class RenderTarget;

struct VisibilityPassDesc {
  std::array<VkDescriptorSetLayout, 4> set_layouts{};  // frame, probe, BRDF, material (SetIndex)
  int sh_order = 2;  // selects visibility_shade_sh<order>[_ms].frag
  std::uint32_t samples = 1;
  // The shading writes the resolve image of a multisampled target without multisampled colour
  // (RenderTargetDesc::multisampled_color false): one sample per pixel, no resolve after it.
  // Only where nothing blends over the shading (no BLEND material).
  bool shade_resolved = false;
  ShaderVariant variant;
};

class VisibilityPass {
 public:
  // Empty when the device can run the pass for these materials; otherwise why not (one line).
  static std::optional<std::string> unsupported(const gpu::Device& device,
                                                const MaterialTextures& materials);

  // Throws GpuError where unsupported() says why, and for an SH order outside 1..4. The
  // meshes and materials must outlive the pass (their buffers are bound once).
  VisibilityPass(const gpu::Device& device, const VisibilityPassDesc& desc, const GpuMeshes& meshes,
                 const MaterialTextures& materials);

  // Builds the geometry pipelines `method` records with: GpuError for layered without
  // shaderOutputLayer.
  void prepare(ViewMethod method);

  // Records the views' opaque and masked instances into the target's layers (view i -> layer
  // i): ids and depth, then the shading over the colour cleared to `clear`. sets: the frame,
  // probe and BRDF sets (SetIndex 0..2). The target's samples and RenderTarget::resolves()
  // must be the desc's (std::logic_error otherwise).
  void record(VkCommandBuffer cmd, const scene::Scene& scene, const GpuMeshes& meshes,
              const MaterialTextures& materials, std::array<VkDescriptorSet, 3> sets,
              const RenderTarget& target, const ForwardViews& views, const glm::vec4& clear);

  std::uint32_t passes_recorded() const { return passes_; }
  const CullStats& cull_stats() const { return stats_; }

  static constexpr VkFormat kIdFormat = VK_FORMAT_R32G32_UINT;

 private:
  VkPipeline geometry_pipeline(bool layered, bool masked);
  void ensure_ids(const RenderTarget& target);
  void write_instances(const scene::Scene& scene, const GpuMeshes& meshes,
                       const MaterialTextures& materials);
  void draw_geometry(VkCommandBuffer cmd, const scene::Scene& scene, const MaterialTextures& materials,
                     bool layered, std::uint32_t view_index, std::uint32_t first_instance);
  void begin_geometry(VkCommandBuffer cmd, const RenderTarget& target, VkImageView ids,
                      VkImageView depth, std::uint32_t layers) const;

  const gpu::Device& device_;
  VisibilityPassDesc desc_;
  PipelineLayout geometry_layout_, shade_layout_;
  gpu::ShaderModule vertex_, opaque_, masked_, fullscreen_, shade_;
  std::optional<gpu::ShaderModule> layered_vertex_;  // loaded on first use
  bool layered_supported_ = false;
  // [layered][masked], each made on first use.
  Pipeline geometry_[2][2];
  Pipeline shade_pipeline_;
  OwnedDescriptorSet set_;  // set 3 of the shading
  Sampler sampler_;         // the ids are read with texelFetch; a combined sampler needs one
  gpu::Buffer instances_;
  gpu::Image ids_;
  std::vector<gpu::ImageView> id_layers_;
  gpu::ImageView id_all_;  // every layer, as a 2D array (also for one view)
  std::uint32_t passes_ = 0;
  CullStats stats_;
  std::vector<std::size_t> order_;  // instances by material, reused
  std::vector<DrawItem> items_;
};

}  // namespace ddish::raster
