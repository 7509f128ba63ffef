// ddish render SCENE [--camera NODE|eye,target,up] [--fov DEG] [--width W --height H]
//                    [--frames N] [--every] [--fps F] [--time T] [--out DIR] [--timings FILE]
//                    [--grid X,Y,Z|auto] [--probe-spacing M] [--sh-order 1..4]
//                    [--probe-samples N] [--hysteresis A] [--bounces N] [--msaa 1|4]
//                    [--sample-shading] [--tonemap linear|filmic] [--no-indirect]
//                    [--device N] [--seed N]
//
// The main job for one view: each frame poses the scene at t = time + k / fps, updates the
// probes in-process, uploads those that changed, rasterizes (raster::Renderer) and writes the
// last frame (every frame with --every) as DIR/frame_NNNN.png (display, tone curve of
// --tonemap) and DIR/frame_NNNN.exr (linear radiance, no curve: what error figures compare).
// Progress goes to stderr, one line per frame; --timings writes per-frame stage milliseconds.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "app/camera_options.h"
#include "app/commands.h"
#include "app/frame_loop.h"
#include "app/probe_options.h"
#include "gpu/context.h"
#include "probes/probe_tracer.h"
#include "probes/probe_volume.h"
#include "probes/tracer_source.h"
#include "raster/renderer.h"
#include "raster/tonemap.h"
#include "scene/gltf_loader.h"
#include "scene/scene.h"
#include "trace/tracer.h"

namespace ddish::app {
namespace {

namespace fs = std::filesystem;

struct RenderArgs {
  std::string scene;
  CameraArgs view{.width = 512, .height = 512};
  ProbeArgs probe;
  int frames = 1;
  bool every = false;
  double fps = 30.0;
  double time = 0.0;
  std::string out = "out";
  std::string timings;
  std::uint32_t msaa = 0;
  bool sample_shading = false;
  std::string tonemap = "filmic";
  bool no_indirect = false;
  std::optional<std::uint32_t> device;
};

void check(const RenderArgs& a) {
  check_probe_options(a.probe);
  parse_pose(a.view.camera);
  raster::parse_tone_curve(a.tonemap);
  if (a.frames < 1) throw std::invalid_argument("--frames must be at least 1");
  if (!(a.fps > 0.0)) throw std::invalid_argument("--fps must be positive");
  if (a.msaa != 0 && a.msaa != 1 && a.msaa != 2 && a.msaa != 4 && a.msaa != 8 && a.msaa != 16)
    throw std::invalid_argument(fmt::format("--msaa must be 1, 2, 4, 8 or 16, got {}", a.msaa));
}

int run_render(const RenderArgs& a) {
  check(a);  // before loading: a bad option should not cost a scene load
  scene::Scene s = scene::load_scene(a.scene);
  s.pose(a.time);
  const Placement placement = place_probes(a.probe, s);
  std::error_code ec;
  fs::create_directories(a.out, ec);
  if (ec || !fs::is_directory(a.out)) throw std::runtime_error("cannot create output directory " + a.out);

  trace::PathOptions path_options;
  path_options.max_bounces = a.probe.bounces;
  trace::Tracer tracer(s, path_options);
  probes::ProbeVolume volume(placement.grid, a.probe.sh_order);
  probes::TracerSource source(tracer);
  const probes::ProbeTracer probe_tracer(source, update_options(a.probe));

  gpu::Context gpu({.device_index = a.device});
  raster::RendererOptions ro;
  ro.msaa = a.msaa;
  ro.sample_shading = a.sample_shading;
  ro.tone_curve = raster::parse_tone_curve(a.tonemap);
  ro.probes = !a.no_indirect;
  raster::Renderer renderer(gpu.device(), s, volume, ro);
  const auto& grid = placement.grid;
  std::fprintf(stderr,
               "render: %s, %zu triangles on %s; %dx%d, %u samples/pixel; probes %dx%dx%d (%s), L%d\n",
               s.path.c_str(), s.triangle_count(), gpu.device().info().name.c_str(), a.view.width,
               a.view.height, renderer.samples(), grid.counts().x, grid.counts().y, grid.counts().z,
               placement.how.c_str(), renderer.sh_order());

  FrameLoop loop(s, tracer, probe_tracer, volume, renderer,
                 [&a](const scene::Scene& posed) { return std::vector<scene::View>{make_view(posed, a.view)}; });
  FrameLoopOptions options;
  options.frames = a.frames;
  options.time = a.time;
  options.fps = a.fps;
  options.every = a.every;
  options.out = a.out;
  const FrameLoopResult result = loop.run(options, [&](const FrameReport& r) {
    const metrics::FrameTimings& t = *r.timings;
    std::fprintf(stderr,
                 "frame %d/%d t=%.3f s: probes %.1f ms (%u traced, %u uploaded in %.1f ms), "
                 "raster %.1f ms (GPU shadow %.1f + forward %.1f + tonemap %.1f), total %.1f ms\n",
                 r.frame + 1, a.frames, r.t, t.stage_ms("probe_update"), r.probes_traced,
                 r.probes_uploaded, t.stage_ms("upload"),
                 t.stage_ms("raster_record") + t.stage_ms("shadow_gpu") + t.stage_ms("forward_gpu") +
                     t.stage_ms("tonemap_gpu") + t.stage_ms("raster_wait"),
                 t.stage_ms("shadow_gpu"), t.stage_ms("forward_gpu"), t.stage_ms("tonemap_gpu"),
                 t.total_ms());
  });
  if (!a.timings.empty()) result.timings.write(a.timings);
  for (const fs::path& p : result.written) std::printf("wrote %s\n", p.string().c_str());
  if (!a.timings.empty()) std::printf("wrote %s\n", a.timings.c_str());
  return 0;
}

Action make_render(CLI::App& root) {
  auto a = std::make_shared<RenderArgs>();
  CLI::App* cmd = root.add_subcommand(
      "render", "the main job: probes updated and views rasterized per frame, written to --out");
  cmd->add_option("scene", a->scene, "glTF 2.0 scene (.gltf or .glb)")->required()->check(CLI::ExistingFile);
  add_camera_options(*cmd, a->view);
  add_probe_options(*cmd, a->probe);
  cmd->add_option("--frames", a->frames, "frames to render")->capture_default_str();
  cmd->add_flag("--every", a->every, "write every frame, not only the last");
  cmd->add_option("--fps", a->fps, "frame k shows the scene at time + k / fps")->capture_default_str();
  cmd->add_option("--time", a->time, "scene time of frame 0 (seconds)")->capture_default_str();
  cmd->add_option("--out", a->out, "output directory")->capture_default_str();
  cmd->add_option("--timings", a->timings, "write per-frame stage milliseconds as JSON here");
  cmd->add_option("--msaa", a->msaa, "samples per pixel (default: 4 where supported, else 1)");
  cmd->add_flag("--sample-shading", a->sample_shading, "shade every MSAA sample");
  cmd->add_option("--tonemap", a->tonemap, "display curve of the PNG: linear or filmic (ACES fit)")
      ->capture_default_str();
  cmd->add_flag("--no-indirect", a->no_indirect, "render without the probes' indirect light");
  cmd->add_option_function<std::uint32_t>(
      "--device", [a](std::uint32_t d) { a->device = d; }, "Vulkan device index (see ddish devices)");
  return [a]() { return run_render(*a); };
}

}  // namespace

DDISH_COMMAND(20, make_render);

}  // namespace ddish::app
