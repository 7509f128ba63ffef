#include "raster/renderer.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <string>

#include "gpu/device.h"
#include "gpu/error.h"
#include "gpu/image.h"
#include "gpu/memory.h"
#include "io/host_memory.h"
#include "probes/probe_volume.h"
#include "scene/scene.h"
#include "scene/view.h"

namespace ddish::raster {

namespace {

enum TimerRange : std::uint32_t { kShadowRange = 0, kForwardRange = 1, kTonemapRange = 2, kRanges = 3 };

double ms_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
}

std::uint32_t choose_samples(const gpu::Device& device, std::uint32_t requested) {
  if (requested != 0) return requested;  // RenderTarget checks it against the device
  return (device.info().msaa_sample_counts() & VK_SAMPLE_COUNT_4_BIT) ? 4u : 1u;
}

ShadowSettings shadow_settings(const RendererOptions& o, const scene::RenderPlan& plan) {
  ShadowSettings s;
  s.map_size = o.shadow_map_size;
  s.cascades = o.cascades;
  s.enabled = plan.direct_lights && plan.shadow_maps;
  s.point_shadows = plan.direct_lights && plan.point_shadows;
  return s;
}

// The most layers any frame can need: the layout depends on the lights only, not the pose.
std::uint32_t shadow_capacity(const scene::Scene& scene, const ShadowSettings& s) {
  std::uint32_t n = 0;
  for (const scene::Light& l : scene.lights) {
    if (l.type == scene::LightType::Directional && s.enabled) n += static_cast<std::uint32_t>(s.cascades);
    if (l.type == scene::LightType::Spot && s.enabled) n += 1;
    if (l.type == scene::LightType::Point && s.point_shadows) n += 6;
  }
  return n;
}

ForwardPassDesc forward_desc(const gpu::Device& device, const RendererOptions& o,
                             const scene::RenderPlan& plan,
                             std::array<VkDescriptorSetLayout, 4> layouts, std::uint32_t samples,
                             int volume_order) {
  ForwardPassDesc d;
  d.set_layouts = layouts;
  d.sh_order = o.sh_order > 0 ? o.sh_order : volume_order;
  d.samples = samples;
  d.sample_shading = o.sample_shading;
  d.variant = variant_for(plan);
  d.variant.probes = o.probes;
  d.shading = o.shading;
  // The trivial floor stays one pass: it is what the full shading is measured against.
  d.depth_prepass = o.shading == Shading::full &&
                    o.depth_prepass.value_or(device.features().post_depth_coverage);
  return d;
}

// RendererOptions::shading_pass resolved: throws GpuError when visibility is asked for where
// it cannot run.
bool use_visibility(const gpu::Device& device, const RendererOptions& o, const MaterialTextures& materials) {
  // The trivial floor stays the forward pass: it is what the full shading is measured against.
  if (o.shading != Shading::full) return false;
  const std::optional<std::string> why = VisibilityPass::unsupported(device, materials);
  // Sample shading and the depth prepass are the forward pass's: asking for either picks it.
  if (!o.shading_pass) return !why && !o.sample_shading && !o.depth_prepass;
  if (*o.shading_pass == ShadingPass::forward) return false;
  if (o.sample_shading)
    throw gpu::GpuError("the visibility pass shades each pixel once; sample shading needs the forward pass");
  if (o.depth_prepass.value_or(false))
    throw gpu::GpuError("the depth prepass belongs to the forward pass, not the visibility pass");
  if (why) throw gpu::GpuError(*why);
  return true;
}

}  // namespace

Renderer::Renderer(gpu::Device& device, const scene::Scene& scene, const probes::ProbeVolume& volume,
                   const RendererOptions& options)
    : device_(device),
      options_(options),
      features_(scene::analyze(scene)),
      plan_(scene::make_plan(features_)),
      shadow_settings_(shadow_settings(options, plan_)),
      samples_(choose_samples(device, options.msaa)),
      pass_bytes_(device.info().type == gpu::DeviceType::cpu
                      ? RendererOptions::kCpuPassBytesPerTriangle * scene.triangle_count()
                      : 0),
      runner_(device),
      meshes_(device, runner_, scene),
      materials_(device, runner_, scene, plan_.texture_sampling, options.anisotropy),
      frame_(device, static_cast<std::uint32_t>(scene.lights.size()),
             shadow_capacity(scene, shadow_settings_)),
      shadows_(device, runner_, shadow_settings_.map_size, shadow_capacity(scene, shadow_settings_),
               frame_.layout(), materials_.layout(), plan_.alpha_test || plan_.alpha_blend),
      probe_textures_(device, volume, options.sh_order),
      brdf_tables_(device, runner_),
      tonemapper_(device) {
  // Checked before the pipelines are built, so the error names the sample count, not a
  // pipeline failure.
  const RenderTarget probe_target(device, {.width = 1, .height = 1, .layers = 1, .samples = samples_});
  (void)probe_target;
  frame_.bind_shadow_maps(shadows_.view(), shadows_.sampler());
  forward_ = std::make_unique<ForwardPass>(
      device, forward_desc(device, options, plan_,
                           {frame_.layout(), probe_textures_.layout(), brdf_tables_.layout(),
                            materials_.layout()},
                           samples_, volume.sh_order()));
  forward_->prepare(options.view_method);
  if (use_visibility(device, options, materials_)) {
    const ForwardPassDesc& f = forward_->desc();
    // Nothing blends over the shading without BLEND materials: it writes the resolved pixels.
    shade_resolved_ = samples_ > 1 && !plan_.alpha_blend;
    visibility_ = std::make_unique<VisibilityPass>(
        device, VisibilityPassDesc{f.set_layouts, f.sh_order, f.samples, shade_resolved_, f.variant}, meshes_,
        materials_);
    visibility_->prepare(options.view_method);
  }
  if (device.info().timestamps_supported()) timer_.emplace(device, kRanges);
  if (scene.environment_map) background_.emplace(device, runner_, *scene.environment_map);
  // The probe set must hold data before the first frame binds it.
  probe_textures_.upload(runner_, volume);
}

ProbeUploadStats Renderer::upload_probes(const probes::ProbeVolume& volume,
                                         std::span<const std::uint32_t> dirty_probes) {
  return probe_textures_.upload(runner_, volume, dirty_probes);
}

ProbeUploadStats Renderer::import_probes(const probes::ProbeVolume& volume, const GpuProbeData& source,
                                         std::span<const std::uint32_t> dirty_probes) {
  return probe_textures_.import(runner_, volume, source, dirty_probes);
}

ProbeUploadStats Renderer::upload_probes(const probes::ProbeVolume& volume) {
  return probe_textures_.upload(runner_, volume);
}

void Renderer::ensure_target(std::uint32_t width, std::uint32_t height, std::uint32_t views) {
  if (target_ && target_->desc().width == width && target_->desc().height == height &&
      target_->desc().layers == views)
    return;
  target_ = std::make_unique<RenderTarget>(
      device_, RenderTargetDesc{.width = width, .height = height, .layers = views, .samples = samples_,
                                .block = options_.view_method == ViewMethod::multiview
                                             ? forward_->views_per_pass()
                                             : 0u,
                                .multisampled_color = !shade_resolved_});
  const VkDeviceSize pixels = VkDeviceSize{width} * height * views;
  // Transfer sources too: a RenderRequest's after_batch may copy views out of them.
  const VkBufferUsageFlags usage =
      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
  hdr_readback_ = gpu::Buffer(device_, pixels * 8, usage, gpu::MemoryUse::readback);
  display_readback_ = gpu::Buffer(device_, pixels * 4, usage, gpu::MemoryUse::readback);
}

void Renderer::record_frame(VkCommandBuffer cmd, const scene::Scene& scene,
                            std::span<const scene::View> views, std::uint32_t layers) {
  if (timer_) timer_->reset(cmd);
  if (timer_) timer_->begin(cmd, kShadowRange);
  shadows_.record(cmd, scene, meshes_, materials_, frame_.set(), layers);
  if (timer_) timer_->end(cmd, kShadowRange);

  target_->begin_frame(cmd);
  if (timer_) timer_->begin(cmd, kForwardRange);
  std::vector<glm::mat4> view_proj;
  std::vector<glm::vec3> eyes;
  for (const scene::View& v : views) {
    view_proj.push_back(v.projection * v.view);
    eyes.push_back(v.eye());
  }
  // A map is composited behind the drawn pixels after the resolve (their alpha is coverage);
  // a uniform sky is the clear colour.
  const glm::vec4 clear = background_ ? glm::vec4(0.0f) : glm::vec4(scene.environment(), 1.0f);
  const std::array<VkDescriptorSet, 3> sets{frame_.set(), probe_textures_.set(), brdf_tables_.set()};
  const ForwardViews forward_views{view_proj, eyes, options_.view_method, options_.cull};
  if (visibility_) {
    visibility_->record(cmd, scene, meshes_, materials_, sets, *target_, forward_views, clear);
    forward_->record_transparent(cmd, scene, meshes_, materials_, sets, *target_, forward_views);
  } else {
    forward_->record(cmd, scene, meshes_, materials_, sets, *target_, forward_views, clear);
  }
  if (timer_) timer_->end(cmd, kForwardRange);
  target_->end_frame(cmd);

  const gpu::Image& resolved = target_->resolved();
  for (std::uint32_t v = 0; v < views.size(); ++v)
    gpu::copy_image_to_buffer(cmd, resolved, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, v, hdr_readback_,
                              resolved.layer_bytes() * v);
  gpu::memory_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_HOST_BIT,
                      VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_HOST_READ_BIT);
  if (background_) background_->record(cmd, hdr_readback_, views, target_->desc().width, target_->desc().height);
  if (timer_) timer_->begin(cmd, kTonemapRange);
  const auto pixels = static_cast<std::uint32_t>(resolved.layer_bytes() / 8 * views.size());
  tonemapper_.record(cmd, hdr_readback_, display_readback_, pixels, options_.tone_curve,
                     options_.exposure);
  if (timer_) timer_->end(cmd, kTonemapRange);
  gpu::memory_barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                      VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
}

bool Renderer::shadows_current(const scene::Scene& scene,
                               const std::vector<ShadowLayerData>& layers) const {
  if (layers.empty() || layers.size() != shadow_layers_.size() ||
      scene.instances.size() != shadow_transforms_.size())
    return false;
  if (std::memcmp(layers.data(), shadow_layers_.data(), layers.size() * sizeof(ShadowLayerData)) != 0)
    return false;
  for (std::size_t i = 0; i < scene.instances.size(); ++i)
    if (scene.instances[i].transform != shadow_transforms_[i]) return false;
  return true;
}

std::uint64_t Renderer::view_bytes(std::uint32_t width, std::uint32_t height) const {
  // MSAA colour (RGBA16F, unless the visibility pass shades the resolve image) and depth (D32)
  // samples, the visibility pass's ids (two uints a sample), the resolve image, the HDR and
  // display readbacks.
  const std::uint64_t sample_bytes = (shade_resolved_ ? 0 : 8) + 4 + (visibility_ ? 8 : 0);
  return std::uint64_t{width} * height * (std::uint64_t{samples_} * sample_bytes + 8 + 8 + 4) + pass_bytes_;
}

std::uint32_t Renderer::fit_memory(std::uint32_t width, std::uint32_t height, std::uint32_t views,
                                   std::uint32_t batch, bool read_back) const {
  const std::uint64_t per_view = view_bytes(width, height);
  // The target being replaced is freed first, so its bytes count as room.
  const std::uint64_t held = target_ ? view_bytes(target_->desc().width, target_->desc().height) *
                                           target_->desc().layers
                                     : 0;
  const bool limited = options_.memory_limit_bytes > 0;
  const std::uint64_t room = limited ? options_.memory_limit_bytes : gpu::device_memory_available(device_) + held;
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  if (per_view > room)
    throw gpu::GpuError("one " + size + " view at " + std::to_string(samples_) + " sample" +
                        (samples_ == 1 ? "" : "s") + " per pixel needs " + io::format_bytes(per_view) +
                        " of device memory (render target, resolve and readback), more than the " +
                        io::format_bytes(room) + (limited ? " that --max-gpu-memory allows" : " the device has free") +
                        ": lower the view size or --msaa");
  batch = static_cast<std::uint32_t>(std::min<std::uint64_t>(batch, room / per_view));
  if (read_back) {
    // The frame's images on the host: linear RGB halves and packed display pixels.
    const std::uint64_t host = std::uint64_t{width} * height * views * (3 * sizeof(std::uint16_t) + 4);
    const std::uint64_t free = io::host_memory_available();
    if (host > free)
      throw gpu::GpuError(std::to_string(views) + " views of " + size + " need " + io::format_bytes(host) +
                          " of memory for their read-back pixels, more than the " + io::format_bytes(free) +
                          " available: fewer views or a smaller view size");
  }
  return std::max<std::uint32_t>(batch, 1);
}

std::uint32_t Renderer::batch_size(std::uint32_t width, std::uint32_t height,
                                   std::uint32_t views) const {
  std::uint32_t g = options_.batch_views;
  if (g == 0) {
    const std::uint64_t per_view = view_bytes(width, height);
    g = static_cast<std::uint32_t>(std::max<std::uint64_t>(1, RendererOptions::kBatchTargetBytes / per_view));
    const std::uint32_t block = forward_->views_per_pass();
    if (options_.view_method == ViewMethod::multiview && g > block) g -= g % block;
  }
  return std::min({g, views, FrameResources::kMaxViews});
}

void Renderer::record_after_batch(VkCommandBuffer cmd, const RenderRequest& request,
                                  std::uint32_t first_view, std::uint32_t count,
                                  std::uint32_t width, std::uint32_t height) const {
  if (!request.after_batch) return;
  // The copy into hdr (transfer) and the tonemap into display (compute) before whatever the
  // caller reads them with.
  gpu::memory_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                      VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_SHADER_WRITE_BIT,
                      VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT |
                          VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                      VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_SHADER_READ_BIT);
  request.after_batch(cmd, BatchViews{hdr_readback_, display_readback_, first_view, count, width,
                                      height});
}

void Renderer::read_views(std::uint32_t w, std::uint32_t h, std::uint32_t count, bool linear,
                          FrameOutput& out) const {
  const std::size_t per_view = std::size_t(w) * h;
  const auto* halves = static_cast<const std::uint16_t*>(hdr_readback_.mapped());
  const auto* display = static_cast<const std::uint32_t*>(display_readback_.mapped());
  for (std::uint32_t v = 0; v < count; ++v) {
    ViewImage img;
    img.width = static_cast<int>(w);
    img.height = static_cast<int>(h);
    if (linear) {
      img.linear = HalfRgbPixels(per_view);
      const std::uint16_t* src = halves + per_view * 4 * v;
      std::uint16_t* dst = img.linear.halves();
      for (std::size_t i = 0; i < per_view; ++i)  // RGBA to RGB: alpha is always 1
        for (int c = 0; c < 3; ++c) dst[3 * i + c] = src[4 * i + c];
    }
    img.display.assign(display + per_view * v, display + per_view * (v + 1));
    out.views.push_back(std::move(img));
  }
}

FrameOutput Renderer::render(const scene::Scene& scene, std::span<const scene::View> views,
                             const RenderRequest& request) {
  if (views.empty()) throw std::invalid_argument("render: no views");
  for (const scene::View& v : views)
    if (v.width != views.front().width || v.height != views.front().height || v.width <= 0 ||
        v.height <= 0)
      throw std::invalid_argument("render: every view needs the same positive size");
  FrameOutput out;
  const auto w = static_cast<std::uint32_t>(views.front().width);
  const auto h = static_cast<std::uint32_t>(views.front().height);
  const auto n = static_cast<std::uint32_t>(views.size());
  std::uint32_t batch = batch_size(w, h, n);
  // Checked only when the target changes (the first frame, a new size): before any allocation.
  const bool same = target_ && target_->desc().width == w && target_->desc().height == h;
  if (!same || target_->desc().layers < batch) batch = fit_memory(w, h, n, batch, request.read_back);
  else batch = target_->desc().layers;
  ensure_target(w, h, batch);
  out.views.reserve(n);

  // The shadow layout (cascades fitted to every view) and the maps are the frame's, drawn by
  // the first batch and read by all.
  // Deformed meshes posed anew are uploaded before anything draws them; their shadows change.
  const bool reshaped = meshes_.update(device_, runner_, scene);
  const ShadowLayout layout = layout_shadows(scene.lights, views, scene.bounds(), shadow_settings_);
  out.stats.shadows_reused = !reshaped && shadows_current(scene, layout.layers);
  std::uint32_t shadow_layers =
      out.stats.shadows_reused ? 0u : static_cast<std::uint32_t>(layout.layers.size());
  for (std::uint32_t first = 0; first < n; first += batch) {
    const std::uint32_t count = std::min(batch, n - first);
    const std::span<const scene::View> part = views.subspan(first, count);
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<ViewData> view_data;
    for (const scene::View& v : part) view_data.push_back({v.projection * v.view, glm::vec4(v.eye(), 1.0f)});
    FrameData frame;
    frame.environment = glm::vec4(scene.environment(), 0.0f);
    frame.counts = {static_cast<std::uint32_t>(layout.lights.size()),
                    static_cast<std::uint32_t>(layout.layers.size()), count, 0u};
    frame.shadow_params = {1.0f / float(shadows_.map_size()), 1.0f,
                           shadows_.filters_linearly() ? 1.0f : 0.0f, 0.0f};
    frame_.update(frame, view_data, layout.lights, layout.layers);

    double record_ms = 0.0;
    auto t_submit = t0;
    runner_.run([&](VkCommandBuffer cmd) {
      record_frame(cmd, scene, part, shadow_layers);
      record_after_batch(cmd, request, first, count, w, h);
      record_ms = ms_since(t0);
      t_submit = std::chrono::steady_clock::now();
    });
    out.stats.record_ms += record_ms;
    out.stats.execute_ms += ms_since(t_submit);
    out.stats.shadow_passes += shadows_.passes_recorded();
    if (shadow_layers > 0) {
      shadow_layers_ = layout.layers;
      shadow_transforms_.clear();
      for (const scene::Instance& inst : scene.instances) shadow_transforms_.push_back(inst.transform);
      shadow_layers = 0;  // the later batches read the maps the first one drew
    }
    // With the visibility pass, the forward pass recorded the transparent passes alone.
    out.stats.forward_passes += forward_->passes_recorded();
    out.stats.cull += forward_->cull_stats();
    if (visibility_) {
      out.stats.forward_passes += visibility_->passes_recorded();
      out.stats.cull += visibility_->cull_stats();
    }
    out.stats.tonemap_passes += 1;
    if (timer_) {
      const std::vector<double> ms = timer_->all_milliseconds();
      out.stats.shadow_gpu_ms += ms[kShadowRange];
      out.stats.forward_gpu_ms += ms[kForwardRange];
      out.stats.tonemap_gpu_ms += ms[kTonemapRange];
    }
    if (!request.read_back) {
      for (std::uint32_t v = 0; v < count; ++v)
        out.views.push_back({.width = static_cast<int>(w), .height = static_cast<int>(h)});
      continue;
    }
    const auto t_read = std::chrono::steady_clock::now();
    read_views(w, h, count, request.linear, out);
    out.stats.readback_ms += ms_since(t_read);
  }
  return out;
}

}  // namespace ddish::raster
