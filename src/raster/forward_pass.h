// The forward pass: every instance drawn for every view with direct light, SH-probe indirect
// light and emission (forward_main.glsl), opaque and masked materials first, then glTF BLEND
// materials in a transparent pass (sorted back to front per instance, blended over what is
// behind, depth tested but not written, lit by the probes like the rest), into an HDR target
// cleared to the environment's radiance (the uniform sky is what a pixel that hits nothing sees; a clear, not a full-screen
// draw, so lavapipe 22's multiview bug with primitives outside the clip volume cannot touch it).
// With an environment map the clear is transparent black instead, alpha being the coverage of
// what was drawn, and raster/environment_background.h composites the map behind it.
// The views go into a layered target, one layer per view, recorded as ViewMethod says, each
// pass drawing only the clusters its views can see when culling is on (raster/draw_list.h).
//
// With a depth prepass (ForwardPassDesc::depth_prepass), each pass first draws its opaque and
// masked instances into depth alone (masked ones discarding as the shading does,
// forward_depth_masked.frag), then shades them with the depth test before the shader and no
// depth writes: a fragment none of whose samples is the nearest skips its lighting
// (forward_sh*_prepassed.frag, post-depth coverage). Each visible surface is then lit about
// once, not once per layer of overdraw; that matters most on lavapipe at MSAA 4, which runs the
// fragment shader of every covered fragment, hidden or not.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <utility>
#include <span>
#include <vector>

#include <glm/glm.hpp>
#include <vulkan/vulkan.h>

#include "gpu/shader.h"
#include "raster/draw_list.h"
#include "raster/graphics_pipeline.h"
#include "raster/shader_variant.h"
#include "raster/shading.h"
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

// Descriptor sets in the order the shaders number them.
enum SetIndex : std::uint32_t { kFrameSet = 0, kProbeSet = 1, kBrdfSet = 2, kMaterialSet = 3 };

struct ForwardPassDesc {
  std::array<VkDescriptorSetLayout, 4> set_layouts{};  // by SetIndex
  int sh_order = 2;             // selects forward_sh<order>.frag
  std::uint32_t samples = 1;
  bool sample_shading = false;  // needs DeviceFeatures::sample_rate_shading
  ShaderVariant variant;
  Shading shading = Shading::full;  // trivial: forward_trivial.frag instead of forward_sh<order>
  // Full shading after a depth prepass (see above); needs DeviceFeatures::post_depth_coverage.
  bool depth_prepass = false;
};

// What one frame's forward pass draws: the views (their matrices also live in the frame set,
// which the shaders read; these are for culling) and how to record them.
struct ForwardViews {
  std::span<const glm::mat4> view_proj;
  std::span<const glm::vec3> eyes;
  ViewMethod method = ViewMethod::per_view;
  bool cull = true;
};

class ForwardPass {
 public:
  // Throws GpuError for a device without sample-rate shading when it is asked for, and for an
  // SH order outside 1..4.
  ForwardPass(const gpu::Device& device, const ForwardPassDesc& desc);

  // Records the views into the target's layers (view i -> layer i). sets holds the frame, probe
  // and BRDF sets (SetIndex 0..2); materials give set 3. Multiview draws a pass per view block
  // of the target (make it with block = views_per_pass()); layered needs the device's
  // shaderOutputLayer (GpuError otherwise).
  void record(VkCommandBuffer cmd, const scene::Scene& scene, const GpuMeshes& meshes,
              const MaterialTextures& materials, std::array<VkDescriptorSet, 3> sets,
              const RenderTarget& target, const ForwardViews& views, const glm::vec4& clear);

  // The transparent pass alone, after another pass drew the opaque and masked instances into
  // the target (raster/visibility_pass.h) and left its colour and depth: each view's BLEND
  // instances, back to front from its eye, one pass per view whatever the view method (a view
  // without any draws none). passes_recorded() and cull_stats() then count these passes.
  void record_transparent(VkCommandBuffer cmd, const scene::Scene& scene, const GpuMeshes& meshes,
                          const MaterialTextures& materials, std::array<VkDescriptorSet, 3> sets,
                          const RenderTarget& target, const ForwardViews& views);

  // Builds the pipeline `method` records with (for multiview, that of a full block), so that a
  // device lacking what it needs fails here, before any recording: GpuError for layered
  // without shaderOutputLayer.
  void prepare(ViewMethod method);

  // Views one multiview pass draws on this device (maxMultiviewViewCount; 1 without multiview).
  std::uint32_t views_per_pass() const { return max_multiview_; }
  std::uint32_t passes_recorded() const { return passes_; }
  const CullStats& cull_stats() const { return stats_; }
  const ForwardPassDesc& desc() const { return desc_; }

 private:
  // What a pipeline draws: the shading of opaque and masked instances, the transparent pass
  // (GraphicsPipelineDesc::alpha_blend), the depth prepass of opaque and of masked instances.
  enum Kind : int { kShade = 0, kBlend = 1, kDepth = 2, kDepthMasked = 3, kKinds = 4 };
  VkPipeline pipeline_for(ViewMethod method, std::uint32_t view_count, Kind kind = kShade);
  // Begins dynamic rendering into the views' colour and depth and binds the pipeline and sets.
  // clear: the colour to clear to (depth to 1); none: draw over what earlier passes left there.
  void begin_pass(VkCommandBuffer cmd, const RenderTarget& target, VkImageView color,
                  VkImageView depth, std::uint32_t layers, std::uint32_t view_mask,
                  const std::optional<glm::vec4>& clear, VkPipeline pipeline,
                  std::span<const VkDescriptorSet> sets) const;
  // depth: the prepass's {opaque, masked} pipelines, bound as the items' materials need them;
  // empty: whatever pipeline is bound draws them all.
  void draw_items(VkCommandBuffer cmd, const scene::Scene& scene, const MaterialTextures& materials,
                  std::span<const DrawItem> items, std::uint32_t view_index,
                  std::uint32_t first_instance,
                  std::array<VkPipeline, 2> depth = {VK_NULL_HANDLE, VK_NULL_HANDLE}) const;
  // The opaque and masked items: the depth prepass (when on), then the shading.
  void draw_opaque(VkCommandBuffer cmd, const scene::Scene& scene, const MaterialTextures& materials,
                   ViewMethod method, std::uint32_t view_count, std::uint32_t view_index,
                   std::uint32_t first_instance);
  // An empty one-view pass that clears a driver's leftover view mask (gpu/driver_quirks.h:
  // lavapipe 25 overruns the next timestamp query pool otherwise).
  void record_view_mask_reset(VkCommandBuffer cmd, const RenderTarget& target) const;

  const gpu::Device& device_;
  ForwardPassDesc desc_;
  PipelineLayout layout_;
  gpu::ShaderModule vertex_, fragment_;
  std::optional<gpu::ShaderModule> depth_masked_;  // with the depth prepass
  std::optional<gpu::ShaderModule> layered_vertex_;  // loaded on first use
  std::uint32_t max_multiview_ = 1;
  bool layered_supported_ = false;
  bool reset_view_mask_ = false;  // after multiview passes: record_view_mask_reset
  // By Kind, each made on first use (the transparent pass's when a scene has BLEND).
  Pipeline pipeline_[kKinds];          // per-view passes
  Pipeline layered_pipeline_[kKinds];
  // By (view mask, kind).
  std::map<std::pair<std::uint32_t, int>, Pipeline> multiview_pipelines_;
  std::uint32_t passes_ = 0;
  CullStats stats_;
  std::vector<DrawItem> items_;        // reused from pass to pass
  std::vector<DrawItem> blend_items_;  // the transparent pass's, likewise
};

}  // namespace ddish::raster
