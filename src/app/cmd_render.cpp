// ddish render SCENE [--display single|stereo|PROFILE] [--views N] [--focal-distance M]
//                    [--per-view] [--calibration FILE.json]
//                    [--camera NODE|eye,target,up] [--fov DEG] [--width W --height H]
//                    [--frames N] [--every] [--loop] [--fps F] [--time T] [--out DIR] [--timings FILE]
//                    [--grid X,Y,Z|auto] [--probe-spacing M] [--sh-order 1..4]
//                    [--probe-samples N] [--hysteresis A] [--bounces N] [--msaa 1|4]
//                    [--sample-shading] [--anisotropy N] [--tonemap linear|filmic] [--no-indirect]
//                    [--sky R,G,B] [--exposure EV]
//                    [--schedule uniform|visibility] [--budget-ms MS] [--max-age N]
//                    [--blend per-update|per-sample] [--device N] [--seed N]
//
// The main job: each frame poses the scene at t = time + k / fps, updates the probes in-process
// ONCE, uploads those that changed, rasterizes all N views of the display (view_options.h) in one
// Renderer::render call, and writes the last frame (every frame with --every) as frame_outputs.h
// says: DIR/frame_NNNN.png/.exr for the single view, a quilt for light-field and grid displays,
// a side-by-side pair for stereo (PNG: display values, tone curve of --tonemap; EXR: linear).
// The probes of each frame are the scheduler's choice (schedule_options.h, frame_loop.h) within
// --budget-ms or the profile's budget. At start the run log (stderr) lists what the scene's
// render plan leaves out and why, as `ddish info` does, and after the first frame how many
// probes were found inside geometry (never traced or uploaded again).
// Progress goes to stderr, one line per frame; --timings writes render_timings.h's JSON.
// With validation on (DDISH_VALIDATION=1) any validation error makes the run exit 1.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "app/camera_options.h"
#include "app/commands.h"
#include "app/frame_loop.h"
#include "app/frame_outputs.h"
#include "app/lighting_options.h"
#include "app/plan_report.h"
#include "app/probe_options.h"
#include "app/render_timings.h"
#include "app/schedule_options.h"
#include "app/view_options.h"
#include "display/calibration.h"
#include "gpu/context.h"
#include "probes/probe_tracer.h"
#include "probes/probe_volume.h"
#include "probes/scheduler.h"
#include "probes/tracer_source.h"
#include "raster/anisotropy.h"
#include "raster/renderer.h"
#include "raster/tonemap.h"
#include "scene/features.h"
#include "scene/gltf_loader.h"
#include "scene/scene.h"
#include "trace/tracer.h"

namespace ddish::app {
namespace {

namespace fs = std::filesystem;

struct RenderArgs {
  std::string scene;
  CameraArgs view{.width = 512, .height = 512};
  DisplayArgs display;
  bool per_view = false;
  std::string calibration;
  ProbeArgs probe;
  LightingArgs lighting;
  ScheduleArgs schedule;
  int frames = 1;
  bool every = false;
  bool loop = false;
  double fps = 30.0;
  double time = 0.0;
  std::string out = "out";
  std::string timings;
  std::uint32_t msaa = 0;
  bool sample_shading = false;
  int anisotropy = raster::kAutomaticAnisotropy;
  std::string tonemap = "filmic";
  bool no_indirect = false;
  std::optional<std::uint32_t> device;
};

void check(const RenderArgs& a) {
  check_probe_options(a.probe);
  check_schedule_options(a.schedule);
  sky_radiance(a.lighting);
  parse_pose(a.view.camera);
  raster::parse_tone_curve(a.tonemap);
  if (a.frames < 1) throw std::invalid_argument("--frames must be at least 1");
  if (!(a.fps > 0.0)) throw std::invalid_argument("--fps must be positive");
  if (a.msaa != 0 && a.msaa != 1 && a.msaa != 2 && a.msaa != 4 && a.msaa != 8 && a.msaa != 16)
    throw std::invalid_argument(fmt::format("--msaa must be 1, 2, 4, 8 or 16, got {}", a.msaa));
  try {
    raster::check_anisotropy(a.anisotropy);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("--") + e.what());
  }
}

// The frame's progress line on stderr.
void print_progress(const FrameReport& r, int frames) {
  const metrics::FrameTimings& t = *r.timings;
  const FrameCounts& c = r.counts;
  const probes::SchedulerFrameRecord& sr = c.schedule;
  const std::string budget =
      sr.budget_ms > 0.0 ? fmt::format(" of budget {:g} ms{}", sr.budget_ms,
                                       sr.within_budget() ? "" : " (over)")
                         : std::string();
  std::fprintf(stderr,
               "frame %d/%d t=%.3f s: %u views; probes %.1f ms (%llu update, %u of %u active "
               "traced at %u samples, %u changed, %u uploaded in %.1f ms), raster %.1f ms = %.2f ms/view "
               "(GPU shadow %.1f + forward %.1f + tonemap %.1f), output %.1f ms, total %.1f "
               "ms%s\n",
               r.frame + 1, frames, r.t, c.views, t.stage_ms("probe_update"),
               static_cast<unsigned long long>(c.probe_updates), c.probes_traced,
               c.probe_updates > 0 ? sr.active : c.probes_active, sr.samples_per_probe,
               c.probes_changed, c.probes_uploaded, t.stage_ms("upload"),
               raster_ms(t), raster_ms(t) / std::max(1u, c.views), t.stage_ms("shadow_gpu"),
               t.stage_ms("forward_gpu"), t.stage_ms("tonemap_gpu"), t.stage_ms("output"),
               t.total_ms(), budget.c_str());
  if (r.frame == 0 && c.probe_updates > 0)
    std::fprintf(stderr, "render: %u of %u probes inside geometry: never traced or uploaded%s\n",
                 c.probes_inactive, c.probes_active + c.probes_inactive,
                 c.probes_unclassified > 0
                     ? fmt::format(" ({} not classified yet: their first update will tell)",
                                   c.probes_unclassified)
                           .c_str()
                     : "");
}

struct GpuRun {
  FrameLoopResult result;
  bool validation = false;  // the validation layer was on
  std::shared_ptr<const gpu::ValidationLog> log;
};

// Everything that holds Vulkan objects lives in here, so that by the time it returns the device
// and instance are destroyed and what the layer says about them (leaks) is in the log.
GpuRun render_frames(const RenderArgs& a, scene::Scene& s, const Placement& placement,
                     const DisplayChoice& choice, const display::ViewSet& first,
                     const FrameWriter& writer) {
  trace::PathOptions path_options;
  path_options.max_bounces = a.probe.bounces;
  trace::Tracer tracer(s, path_options);
  probes::ProbeVolume volume(placement.grid, a.probe.sh_order);
  probes::TracerSource source(tracer);
  probes::ProbeTracer probe_tracer(source, update_options(a.probe));
  const double budget_ms = frame_budget_ms(
      a.schedule, choice.profile ? choice.profile->budget_ms() : std::optional<double>());
  probes::Scheduler scheduler(scheduler_options(a.schedule, a.probe, budget_ms));

  GpuRun run;
  gpu::Context gpu({.device_index = a.device});
  run.validation = gpu.instance().validation_enabled();
  run.log = gpu.instance().shared_validation();
  raster::RendererOptions ro;
  ro.msaa = a.msaa;
  ro.sample_shading = a.sample_shading;
  ro.anisotropy = a.anisotropy;
  ro.tone_curve = raster::parse_tone_curve(a.tonemap);
  ro.exposure = exposure_scale(a.lighting);
  ro.probes = !a.no_indirect;
  raster::Renderer renderer(gpu.device(), s, volume, ro);
  const auto& grid = placement.grid;
  std::fprintf(stderr,
               "render: %s, %zu triangles on %s; display %s: %zu views of %dx%d (%dx%d atlas %dx%d), "
               "%u samples/pixel; probes %dx%dx%d (%s), L%d\n",
               s.path.c_str(), s.triangle_count(), gpu.device().info().name.c_str(),
               first.name.c_str(), first.size(), first.layout.tile_width,
               first.layout.tile_height, first.layout.columns, first.layout.rows,
               first.layout.width, first.layout.height, renderer.samples(), grid.counts().x,
               grid.counts().y, grid.counts().z, placement.how.c_str(), renderer.sh_order());

  const probes::SchedulerOptions& so = scheduler.options();
  std::fprintf(stderr, "render: schedule %s, blend %s, max age %u frames, budget %s\n",
               probes::schedule_mode_name(so.mode), probes::blend_rule_name(so.blend),
               so.priority.max_age,
               budget_ms > 0.0 ? fmt::format("{:g} ms per frame", budget_ms).c_str() : "none");
  std::fprintf(stderr, "render: left out\n");
  for (const std::string& line : left_out_lines(scene::make_plan(scene::analyze(s)), "  "))
    std::fprintf(stderr, "%s\n", line.c_str());

  // The views are rebuilt from the posed scene every frame: an animated camera node moves the
  // whole rig.
  FrameLoop loop(
      s, tracer, probe_tracer, scheduler,
      [&](const probes::FramePlan& plan) {
        return frame_update_options(a.schedule, a.probe, plan.samples, plan.hysteresis);
      },
      volume, renderer, [&](const scene::Scene& posed) {
        return make_frame_views(posed, choice, a.display, a.view).views;
      });
  FrameLoopOptions options;
  options.frames = a.frames;
  options.time = a.time;
  options.fps = a.fps;
  options.every = a.every;
  options.loop_period = a.loop ? s.animation_duration() : 0.0;
  // Without indirect light nothing reads the probes: tracing them would only cost time (and
  // would make a direct-light-only run's frame time meaningless as a baseline).
  options.update_probes = !a.no_indirect;
  if (a.no_indirect) std::fprintf(stderr, "render: --no-indirect: probes are neither traced nor drawn\n");
  const FrameSink sink = [&](int k, const raster::FrameOutput& frame) {
    const std::string tag = a.every ? fmt::format("{:04d}", k) : "";
    return writer.write(frame_images(frame), fmt::format("frame_{:04d}", k), tag);
  };
  run.result = loop.run(options, sink, [&](const FrameReport& r) { print_progress(r, a.frames); });
  return run;
}

int run_render(const RenderArgs& a) {
  check(a);  // before loading: a bad option should not cost a scene load
  const DisplayChoice choice = resolve_display(a.display, a.view);
  std::optional<display::Calibration> calibration;
  if (!a.calibration.empty()) calibration = display::load_calibration(a.calibration);
  scene::Scene s = scene::load_scene(a.scene);
  s.pose(a.time);
  const std::string framing = frame_camera_less(s, a.view, view_aspect(choice, a.view));
  const std::string environment = apply_lighting(s, a.lighting);
  const Placement placement = place_probes(a.probe, s);
  const display::ViewSet first = make_frame_views(s, choice, a.display, a.view);
  const FrameWriter writer(first, {.dir = a.out,
                                   .stem = fs::path(a.scene).stem().string(),
                                   .per_view = a.per_view,
                                   .calibration = calibration});
  std::error_code ec;
  fs::create_directories(a.out, ec);
  if (ec || !fs::is_directory(a.out)) throw std::runtime_error("cannot create output directory " + a.out);

  // Said once the views and outputs are known to be good: bad input gets its one error line only.
  if (!framing.empty()) std::fprintf(stderr, "render: %s\n", framing.c_str());
  std::fprintf(stderr, "render: %s\n", environment.c_str());
  const GpuRun run = render_frames(a, s, placement, choice, first, writer);
  if (!a.timings.empty()) write_render_timings(a.timings, run.result.timings, run.result.counts, first);
  for (const fs::path& p : run.result.written) std::printf("wrote %s\n", p.string().c_str());
  if (!a.timings.empty()) std::printf("wrote %s\n", a.timings.c_str());
  if (run.validation) {
    const std::uint32_t errors = run.log->errors();
    std::fprintf(stderr, "render: validation: %u errors, %u warnings\n", errors,
                 run.log->warnings());
    if (errors > 0) {
      const std::vector<std::string> messages = run.log->error_messages();
      std::fprintf(stderr, "ddish: error: Vulkan validation reported %u error%s (first: %s)\n",
                   errors, errors == 1 ? "" : "s",
                   messages.empty() ? "not kept" : messages.front().c_str());
      return 1;
    }
  }
  return 0;
}

Action make_render(CLI::App& root) {
  auto a = std::make_shared<RenderArgs>();
  CLI::App* cmd = root.add_subcommand(
      "render", "the main job: probes updated and views rasterized per frame, written to --out");
  cmd->add_option("scene", a->scene, "glTF 2.0 scene (.gltf or .glb)")->required()->check(CLI::ExistingFile);
  add_camera_options(*cmd, a->view);
  add_display_options(*cmd, a->display);
  cmd->add_flag("--per-view", a->per_view, "also write every view as DIR/view_NN.png and .exr");
  cmd->add_option("--calibration", a->calibration,
                  "Looking Glass calibration (visual.json): also write the lenticular panel image")
      ->check(CLI::ExistingFile);
  add_probe_options(*cmd, a->probe);
  add_lighting_options(*cmd, a->lighting, /*exposure=*/true);
  add_schedule_options(*cmd, a->schedule);
  cmd->add_option("--frames", a->frames, "frames to render")->capture_default_str();
  cmd->add_flag("--every", a->every, "write every frame, not only the last");
  cmd->add_flag("--loop", a->loop,
                "play the animations again and again: the scene time wraps at the longest "
                "animation's duration (without it the last pose holds)");
  cmd->add_option("--fps", a->fps, "frame k shows the scene at time + k / fps")->capture_default_str();
  cmd->add_option("--time", a->time, "scene time of frame 0 (seconds)")->capture_default_str();
  cmd->add_option("--out", a->out, "output directory")->capture_default_str();
  cmd->add_option("--timings", a->timings, "write per-frame stage milliseconds as JSON here");
  cmd->add_option("--msaa", a->msaa, "samples per pixel (default: 4 where supported, else 1)");
  cmd->add_flag("--sample-shading", a->sample_shading, "shade every MSAA sample");
  cmd->add_option("--anisotropy", a->anisotropy,
                  "texture anisotropic filtering: maximum 2..16 (clamped to the device), 1 off, "
                  "0 automatic: 8 on GPUs, off on CPU devices (lavapipe, where it can stall a view)")
      ->capture_default_str();
  cmd->add_option("--tonemap", a->tonemap, "display curve of the PNG: linear or filmic (ACES fit)")
      ->capture_default_str();
  cmd->add_flag("--no-indirect", a->no_indirect,
                "direct light only: the probes are neither traced nor drawn");
  cmd->add_option_function<std::uint32_t>(
      "--device", [a](std::uint32_t d) { a->device = d; }, "Vulkan device index (see ddish devices)");
  return [a]() { return run_render(*a); };
}

}  // namespace

DDISH_COMMAND(20, make_render);

}  // namespace ddish::app
