// The rasterizer of one frame: shadow maps -> forward pass (direct + SH-probe indirect +
// emission, environment behind) -> tonemap, for a list of views that share one probe volume,
// read back as linear HDR pixels (for EXR files and error figures) and tonemapped RGBA8 display
// pixels. Everything view-independent (geometry, materials, probe textures, shadow maps) is made
// once per frame or once per scene; what multiplies with the views is the forward pass alone.
//
//   raster::Renderer renderer(gpu.device(), scene, volume, {});
//   renderer.upload_probes(volume, dirty);        // after each probe update
//   raster::FrameOutput out = renderer.render(scene, views);
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "gpu/buffer.h"
#include "gpu/commands.h"
#include "gpu/timestamps.h"
#include "raster/brdf_tables.h"
#include "raster/environment_background.h"
#include "raster/forward_pass.h"
#include "raster/frame_resources.h"
#include "raster/half_rgb_pixels.h"
#include "raster/gpu_meshes.h"
#include "raster/material_textures.h"
#include "raster/probe_textures.h"
#include "raster/render_request.h"
#include "raster/render_target.h"
#include "raster/shadow_layout.h"
#include "raster/shading.h"
#include "raster/shading_pass.h"
#include "raster/shadow_maps.h"
#include "raster/tonemap.h"
#include "raster/view_method.h"
#include "raster/visibility_pass.h"
#include "scene/features.h"

namespace ddish::gpu {
class Device;
}

namespace ddish::scene {
struct Scene;
struct View;
}  // namespace ddish::scene

namespace ddish::probes {
class ProbeVolume;
}

namespace ddish::raster {

struct RendererOptions {
  std::uint32_t msaa = 0;         // samples per pixel; 0: 4 where the device has it, else 1
  bool sample_shading = false;    // shade every sample (sampleRateShading)
  int sh_order = 0;               // SH order the shader evaluates; 0: the volume's
  bool probes = true;             // false: no indirect light (comparisons, debugging)
  ToneCurve tone_curve = ToneCurve::filmic;
  float exposure = 1.0f;          // display pixels only; the linear pixels are never scaled
  std::uint32_t shadow_map_size = 1024;
  int cascades = 3;               // per directional light, 1..4
  // How the views are recorded (raster/view_method.h, with the measurements): one pass per view
  // ties with layered and works on every device; multiview is faster on lavapipe but wrong there.
  ViewMethod view_method = ViewMethod::per_view;
  // Per-view frustum and backface-cone culling of mesh clusters: never changes an image, costs
  // under 2 ms of CPU for 48 views of a 262k-triangle room.
  bool cull = true;
  // Material sampler's maximum anisotropy: 0 automatic (8 on GPUs, off on CPU devices such as
  // lavapipe, where it can stall a view for seconds: raster/anisotropy.h), 1 off, 2..16 asked
  // for (clamped to the device's limit). Outside 0..16: std::invalid_argument.
  int anisotropy = 0;
  // full: the renderer's shading; trivial: a constant colour, the fill-rate floor (raster/shading.h).
  Shading shading = Shading::full;
  // Full shading after a depth prepass (raster/forward_pass.h): unset, wherever the device
  // has VK_EXT_post_depth_coverage; true there only (GpuError elsewhere); false, never.
  std::optional<bool> depth_prepass;
  // Which pass shades (raster/shading_pass.h): unset, the visibility pass wherever the device
  // can run it (VisibilityPass::unsupported), the shading is full and neither sample shading
  // nor depth_prepass is asked for (both belong to the forward pass), else the forward pass;
  // visibility where it cannot run, or with either of those: GpuError.
  std::optional<ShadingPass> shading_pass;
  // Views drawn per submission into one reused target: 0 picks the most whose target and
  // readback fit kBatchTargetBytes (at least one; a multiple of a multiview pass). The
  // device memory of a frame then stops growing with the views (48 views of 420x560 at
  // MSAA 4 draw in three batches of 16); only the read-back images grow, 10 bytes a pixel.
  std::uint32_t batch_views = 0;
  static constexpr std::uint64_t kBatchTargetBytes = 256ull << 20;
  // On a CPU device (lavapipe) each pass's binned triangles stay in memory until its submission
  // ends: Sponza (262k triangles) measured 57 MB a view of a batch beyond its target (16 views:
  // 1.84 GB in one batch, 1.15 GB in batches of 4), so the automatic batch counts this too.
  static constexpr std::uint64_t kCpuPassBytesPerTriangle = 256;
  // The most bytes a frame's render target and readback may take (--max-gpu-memory); 0: what
  // the device has free (gpu::device_memory_available). A batch is made smaller to fit, and a
  // single view that cannot fit is a GpuError before anything is allocated.
  std::uint64_t memory_limit_bytes = 0;
};

struct ViewImage {
  int width = 0;
  int height = 0;
  HalfRgbPixels linear;                 // row 0 at the top, linear radiance (the target's halves)
  std::vector<std::uint32_t> display;   // packed RGBA8 (R in the low byte), sRGB-encoded
};

struct FrameStats {
  std::uint32_t shadow_passes = 0;   // depth passes (one per shadow layer) recorded this frame
  bool shadows_reused = false;       // nothing moved since the last frame: last frame's maps kept
  std::uint32_t forward_passes = 0;  // one per view, per multiview block, or one (layered)
  CullStats cull;                    // clusters and triangles the forward passes drew
  std::uint32_t tonemap_passes = 0;
  // GPU milliseconds from timestamps; 0 where the device has no timestamps.
  double shadow_gpu_ms = 0.0;
  double forward_gpu_ms = 0.0;
  double tonemap_gpu_ms = 0.0;
  double record_ms = 0.0;   // CPU: writing frame data and recording commands
  double execute_ms = 0.0;  // CPU wall time from submission until the GPU finished
  double readback_ms = 0.0; // CPU: converting the read-back pixels
};

struct FrameOutput {
  std::vector<ViewImage> views;
  FrameStats stats;
};

class Renderer {
 public:
  // Uploads the scene's geometry and materials and builds the pipelines for the variant its
  // SceneFeatures call for. Throws GpuError when the device lacks what the options ask for
  // (an MSAA count, sample shading) or what the renderer needs (formats, mip blits).
  Renderer(gpu::Device& device, const scene::Scene& scene, const probes::ProbeVolume& volume,
           const RendererOptions& options = {});

  // Copies the listed probes (all of them the first time) to the GPU; returns what was sent.
  ProbeUploadStats upload_probes(const probes::ProbeVolume& volume,
                                 std::span<const std::uint32_t> dirty_probes);
  ProbeUploadStats upload_probes(const probes::ProbeVolume& volume);
  // The same probes converted on the device from GPU-resident averages (ProbeTextures::import):
  // the hand-off of a probe tracer on this renderer's device, with no CPU copy of the values.
  ProbeUploadStats import_probes(const probes::ProbeVolume& volume, const GpuProbeData& source,
                                 std::span<const std::uint32_t> dirty_probes);

  // Renders the scene as posed now from every view (all of one size) and reads the images back,
  // in batches of batch_size() views that share the frame's shadow maps. `request` may keep
  // the pixels on the GPU and add commands after each batch (raster/render_request.h).
  FrameOutput render(const scene::Scene& scene, std::span<const scene::View> views,
                     const RenderRequest& request = {});
  // Views per submission for views of this size (RendererOptions::batch_views).
  std::uint32_t batch_size(std::uint32_t width, std::uint32_t height, std::uint32_t views) const;

  const scene::SceneFeatures& features() const { return features_; }
  const scene::RenderPlan& plan() const { return plan_; }
  const ShaderVariant& variant() const { return forward_->desc().variant; }
  std::uint32_t samples() const { return samples_; }
  // The material sampler's maxAnisotropy on this device (RendererOptions::anisotropy); 1: off.
  float anisotropy() const { return materials_.max_anisotropy(); }
  int sh_order() const { return forward_->desc().sh_order; }
  // Whether the forward pass shades after a depth prepass (RendererOptions::depth_prepass).
  bool depth_prepass() const { return !visibility_ && forward_->desc().depth_prepass; }
  // Which pass shades (RendererOptions::shading_pass as resolved for this device).
  ShadingPass shading_pass() const { return visibility_ ? ShadingPass::visibility : ShadingPass::forward; }

 private:
  void ensure_target(std::uint32_t width, std::uint32_t height, std::uint32_t views);
  // Device bytes of one view in a batch: MSAA colour and depth, resolve, readbacks, CPU passes.
  std::uint64_t view_bytes(std::uint32_t width, std::uint32_t height) const;
  // The batch that fits the memory (RendererOptions::memory_limit_bytes) for a new target;
  // throws GpuError when one view does not, or when the views' read-back pixels (16 bytes a
  // pixel, host memory) cannot fit the system's available memory.
  std::uint32_t fit_memory(std::uint32_t width, std::uint32_t height, std::uint32_t views,
                           std::uint32_t batch, bool read_back) const;
  void record_frame(VkCommandBuffer cmd, const scene::Scene& scene,
                    std::span<const scene::View> views, std::uint32_t layers);
  // The batch's part of a RenderRequest: makes hdr and display readable, records after_batch.
  void record_after_batch(VkCommandBuffer cmd, const RenderRequest& request,
                          std::uint32_t first_view, std::uint32_t count, std::uint32_t width,
                          std::uint32_t height) const;
  // Converts the first `count` read-back views of the last submission into images (their linear
  // pixels only when `linear`: RenderRequest::linear).
  void read_views(std::uint32_t width, std::uint32_t height, std::uint32_t count, bool linear,
                  FrameOutput& out) const;
  // Whether the shadow maps already hold `layers` for the scene as posed now.
  bool shadows_current(const scene::Scene& scene, const std::vector<ShadowLayerData>& layers) const;

  gpu::Device& device_;
  RendererOptions options_;
  scene::SceneFeatures features_;
  scene::RenderPlan plan_;
  ShadowSettings shadow_settings_;
  std::uint32_t samples_ = 1;
  std::uint64_t pass_bytes_ = 0;  // per view, beyond its target: kCpuPassBytesPerTriangle on CPUs
  gpu::CommandRunner runner_;
  GpuMeshes meshes_;
  MaterialTextures materials_;
  FrameResources frame_;
  ShadowMaps shadows_;
  ProbeTextures probe_textures_;
  BrdfTables brdf_tables_;
  std::unique_ptr<ForwardPass> forward_;
  std::unique_ptr<VisibilityPass> visibility_;  // the shading pass when it is the visibility pass
  bool shade_resolved_ = false;  // VisibilityPassDesc::shade_resolved: the target keeps no MSAA colour
  Tonemapper tonemapper_;
  std::optional<EnvironmentBackground> background_;  // the scene's environment map, if any
  std::optional<gpu::TimestampQueries> timer_;
  std::unique_ptr<RenderTarget> target_;
  gpu::Buffer hdr_readback_;      // RGBA16F pixels of a batch's views, view after view
  gpu::Buffer display_readback_;  // packed RGBA8 pixels, same order
  // What the shadow maps were last rendered for: a static scene seen from a still camera
  // (every frame of a scene without animation) keeps its maps instead of redrawing them.
  std::vector<ShadowLayerData> shadow_layers_;
  std::vector<glm::mat4> shadow_transforms_;
};

}  // namespace ddish::raster
