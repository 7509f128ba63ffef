// ddish render SCENE [--display single|stereo|PROFILE] [--views N] [--focal-distance M]
//                    [--per-view] [--formats png,exr] [--calibration FILE.json]
//                    [--camera NODE|eye,target,up] [--fov DEG] [--width W --height H]
//                    [--frames N] [--every[=N]] [--loop] [--fps F] [--time T] [--out DIR] [--timings FILE]
//                    [--grid X,Y,Z|auto] [--probe-spacing M] [--sh-order 1..4]
//                    [--probe-samples N] [--hysteresis A] [--bounces N] [--msaa 1|4]
//                    [--sample-shading] [--depth-prepass auto|on|off]
//                    [--shading-pass auto|forward|visibility] [--view-batch N]
//                    [--anisotropy N] [--tonemap linear|filmic]
//                    [--no-indirect] [--sky R,G,B] [--exposure EV]
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
// Ctrl-C / SIGTERM (app/interrupt.h): the frame in progress is finished and written as the
// last one, --timings has the frames done, and the exit code is 128 + the signal; every file is
// written whole (io/atomic_file.h), and the output folders are tried before the scene loads.
//
// ddish view SCENE --connect tcp://HOST:PORT[,...] [--relay tcp://HOST:PORT] [--probes FILE]
//                  [--wait-ms MS] [--frame-wait-ms MS]
//                  [--stale-ms MS] [--curve-server-key FILE --curve-secret FILE]
//                  [every option of render but the probe update's and the schedule's]
// is the same loop with the probe stream's client as its probe source (remote_probes.h): the
// probes come from a `ddish serve` of the same scene and probe grid (checked by the scene
// identity, scene_identity.h; the grid's bounds are taken from the server's stream description,
// so a grid that serve --probe-placement fit moved is the client's too), the views go upstream
// to its scheduler. Without a server at start
// it renders with --probes FILE (a volume of `ddish probes --out`), else with direct light only,
// and says which; a lost server leaves the last probes in place. Several --connect servers
// split the probe bricks between them (serve --bricks I/N); the client subscribes only to the
// bricks its views need, through one `ddish relay` with --relay. With --curve-server-key (the
// server's .pub) and --curve-secret (this client's .key) it speaks CurveZMQ.
#include <sys/resource.h>

#include <algorithm>
#include <atomic>
#include <limits>
#include <chrono>
#include <csignal>
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
#include "app/interrupt.h"
#include "app/live_controls.h"
#include "app/live_window.h"
#include "app/lighting_options.h"
#include "app/option_checks.h"
#include "app/output_queue.h"
#include "app/plan_report.h"
#include "app/frame_progress.h"
#include "app/probe_setup.h"
#include "app/raster_options.h"
#include "app/tracer_choice.h"
#include "app/probe_options.h"
#include "app/remote_probes.h"
#include "app/render_timings.h"
#include "app/scene_identity.h"
#include "app/schedule_options.h"
#include "app/view_options.h"
#include "app/warmup_options.h"
#include "display/calibration.h"
#include "display/lenticular.h"
#include "gpu/context.h"
#include "io/atomic_file.h"
#include "net/curve_keys.h"
#include "net/endpoint.h"
#include "probes/probe_tracer.h"
#include "probes/probe_volume.h"
#include "probes/scheduler.h"
#include "probes/tracer_source.h"
#include "probes/volume_file.h"
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
  std::vector<std::string> formats{"png", "exr"};  // --formats
  std::string calibration;
  ProbeArgs probe;
  LightingArgs lighting;
  ScheduleArgs schedule;
  int frames = 1;
  bool frames_given = false;  // --window without --frames runs until closed, writing no files
  LiveArgs live;
  bool monitor_given = false;
  int every = 0;  // --every[=N]: write frames k with (k + 1) % N == 0 too; 0 only the last
  bool loop = false;
  double fps = 30.0;
  double time = 0.0;
  std::string out = "out";
  std::string timings;
  RasterArgs raster;
  std::string tonemap = "filmic";
  bool no_indirect = false;
  std::optional<std::uint32_t> device;
  std::string tracer = "auto";  // --tracer (render's in-process probes)
  bool probe_readback = false;  // --probe-readback: no GPU-resident hand-off
  // `ddish view`: the probe stream's client is the probe source.
  std::string connect;   // empty: `ddish render`, in-process probes
  std::string baked;     // --probes FILE: the probes until a server answers
  int wait_ms = 2000;    // frame 0's wait for the server's snapshot
  int stale_ms = 1000;   // no message for this long, connected: the server is slow
  int frame_wait_ms = 0;  // later frames' wait for the server's next frame
  std::string curve_server_key;  // the server's .pub
  std::string curve_secret;      // this client's .key
  std::string relay;             // --relay: the frames through a ddish relay
  WarmupOptions warmup;  // render: on by default; view: its probes come from the server
  const char* tag() const { return connect.empty() ? "render" : "view"; }
};

bool writes_format(const RenderArgs& a, const char* format) {
  return std::find(a.formats.begin(), a.formats.end(), format) != a.formats.end();
}

void check(const RenderArgs& a) {
  if (a.scene.empty()) throw std::invalid_argument("scene is required (see ddish --help)");  // as CLI11 says it
  check_frame_options(a.probe, a.schedule, a.warmup, a.lighting, a.view, a.tonemap);
  if (a.frames < 1) throw std::invalid_argument("--frames must be at least 1");
  if (!a.live.window &&
      (a.monitor_given || a.live.fullscreen || a.live.mailbox || a.live.hold || a.live.no_status))
    throw std::invalid_argument("--monitor, --fullscreen, --mailbox, --hold and --no-status go with --window");
  if (a.live.hold && !a.frames_given)
    throw std::invalid_argument("--hold keeps the last of --frames N on screen: give --frames");
  if (a.monitor_given && a.live.monitor < 0) throw std::invalid_argument("--monitor must be 0 or more");
  if (a.live.window && !window::display_server_named())
    throw std::invalid_argument("--window needs a display server, and neither DISPLAY nor "
                                "WAYLAND_DISPLAY is set; without --window ddish renders to files");
  if (a.wait_ms < 0 || a.frame_wait_ms < 0 || a.stale_ms < 1)
    throw std::invalid_argument("--wait-ms and --frame-wait-ms must be >= 0, --stale-ms >= 1");
  if (!a.connect.empty()) net::parse_endpoint_list(a.connect);  // throws with the reason
  if (!a.relay.empty()) net::parse_endpoint(a.relay);
  if (a.curve_server_key.empty() != a.curve_secret.empty())
    throw std::invalid_argument("--curve-server-key and --curve-secret go together");
  if (!(a.fps > 0.0)) throw std::invalid_argument("--fps must be positive");
  check_raster_options(a.raster);
}

// Lavapipe keeps device memory in memfd files, which a file size limit (RLIMIT_FSIZE) caps too:
// at the limit the driver's ftruncate fails and its next store to that memory is a SIGBUS.
void check_file_size_limit(const gpu::DeviceInfo& device) {
  rlimit limit{};
  if (device.type != gpu::DeviceType::cpu || ::getrlimit(RLIMIT_FSIZE, &limit) != 0 ||
      limit.rlim_cur == RLIM_INFINITY)
    return;
  throw std::runtime_error(fmt::format(
      "a file size limit of {} bytes is set (ulimit -f): {} keeps device memory in files under "
      "that limit and would crash at it; lift the limit or use a GPU",
      static_cast<unsigned long long>(limit.rlim_cur), device.name));
}

struct GpuRun {
  FrameLoopResult result;
  bool window_closed = false;  // the live window's close (or Esc) ended the run
  bool validation = false;  // the validation layer was on
  std::shared_ptr<const gpu::ValidationLog> log;
};

StreamArgs stream_args(const RenderArgs& a) {
  return {.connect = a.connect,
          .baked = a.baked,
          .wait_ms = a.wait_ms,
          .stale_ms = a.stale_ms,
          .frame_wait_ms = a.frame_wait_ms,
          .curve_server_key = a.curve_server_key,
          .curve_secret = a.curve_secret,
          .relay = a.relay};
}

// Everything that holds Vulkan objects lives in here, so that by the time it returns the device
// and instance are destroyed and what the layer says about them (leaks) is in the log.
GpuRun render_frames(const RenderArgs& a, scene::Scene& s, const Placement& placement,
                     const StreamArgs& stream, const DisplayChoice& choice, const display::ViewSet& first,
                     const FrameWriter& writer, std::uint64_t identity,
                     const std::optional<display::Calibration>& calibration, TimingsFile* timings) {
  const bool remote = !a.connect.empty();
  std::optional<TracerDecision> tracer;
  if (!remote) {
    tracer = choose_tracer(a.tracer, a.device);
    std::fprintf(stderr, "%s: probe tracer %s\n", a.tag(), tracer->why.c_str());
  }
  const bool gpu_tracer = tracer && tracer->kind == TracerKind::vulkan;
  probes::ProbeVolume volume = remote ? starting_volume(a.probe, stream, placement, a.tag())
                                      : local_volume(a.probe, placement.grid);
  const std::uint32_t empty_probes = remote ? 0 : leave_out_empty_probes(volume, s);

  GpuRun run;
  // The live window opens before the GPU context: its surface extensions go into the instance.
  std::unique_ptr<LiveWindow> live;
  if (a.live.window) {
    const scene::Camera start = resolve_camera(s, a.view);
    const float focal = first.kind == display::ViewSetKind::Single
                            ? display::focal_distance_to_scene_center(s, start.eye, start.forward)
                            : a.display.focal_distance.value_or(display::focal_distance_to_scene_center(
                                  s, start.eye, start.forward));
    live = std::make_unique<LiveWindow>(
        a.live, "ddish " + first.name, calibration ? calibration->screen_width : first.layout.width,
        calibration ? calibration->screen_height : first.layout.height,
        choice.profile && choice.profile->panel ? choice.profile->panel->width : 0,
        choice.profile && choice.profile->panel ? choice.profile->panel->height : 0, start, focal);
  }
  // The GPU probe tracer shares the renderer's device (ray tracing switched on for it), so its
  // probes stay on the device that draws them.
  gpu::Context gpu({.device_index = a.device,
                    .instance_extensions = live ? live->instance_extensions() : std::vector<std::string>{},
                    .device_extensions = live ? LiveWindow::device_extensions() : std::vector<std::string>{},
                    .ray_tracing = gpu_tracer});
  // The in-process probe parts hold Vulkan objects when they trace on the GPU: made after the
  // context, destroyed before it.
  std::unique_ptr<InProcessParts> local;
  if (tracer)
    local = make_in_process(a.probe, a.schedule, s,
                            frame_budget_ms(a.schedule, choice.profile ? choice.profile->budget_ms() : std::optional<double>()),
                            tracer->kind, a.device, gpu_tracer ? &gpu.device() : nullptr);
  // The Vulkan tracer shares the renderer's device: the probes it traces go to the rasterizer on
  // the GPU (ProbeEngine::keep_probes_on_device), the CPU volume is read back only on demand.
  if (local && local->engine.keep_probes_on_device(!a.probe_readback))
    std::fprintf(stderr, "%s: traced probes stay on the GPU (converted there for the rasterizer)\n", a.tag());
  LiveAttachment attachment;  // the window's GPU half goes before the context
  check_file_size_limit(gpu.device().info());
  run.validation = gpu.instance().validation_enabled();
  run.log = gpu.instance().shared_validation();
  raster::RendererOptions ro = renderer_options(a.raster);
  ro.tone_curve = raster::parse_tone_curve(a.tonemap);
  ro.exposure = exposure_scale(a.lighting);
  ro.probes = !a.no_indirect;
  raster::Renderer renderer(gpu.device(), s, volume, ro);
  if (live) {
    live->attach(gpu, first.layout, int(first.size()),
                 calibration ? std::optional(display::lenticular_mapping(*calibration)) : std::nullopt);
    attachment.live = live.get();
    for (const std::string& m : window::Window::monitors())
      std::fprintf(stderr, "%s: monitor %s\n", a.tag(), m.c_str());
    std::fprintf(stderr, "%s: window %dx%d on monitor %d: %s %dx%d, %s\n", a.tag(),
                 int(live->window().drawable_size().width), int(live->window().drawable_size().height),
                 live->window().monitor(), calibration ? "lenticular panel image" : "atlas", live->output_width(),
                 live->output_height(), a.live.mailbox ? "mailbox where offered" : "FIFO");
    const auto& panel = choice.profile ? choice.profile->panel : std::nullopt;
    if (panel && !calibration)
      std::fprintf(stderr, "%s: the window shows the quilt (for Looking Glass Bridge or a capture "
                   "card); --calibration with the device's visual.json shows the %dx%d panel image\n",
                   a.tag(), panel->width, panel->height);
    if (panel && calibration &&
        (calibration->screen_width != panel->width || calibration->screen_height != panel->height))
      std::fprintf(stderr, "%s: note: the calibration is for a %dx%d panel, the %s profile's is %dx%d\n",
                   a.tag(), calibration->screen_width, calibration->screen_height,
                   choice.profile->name.c_str(), panel->width, panel->height);
  }
  const auto& grid = placement.grid;
  std::fprintf(stderr,
               "%s: %s, %zu triangles on %s; display %s: %zu views of %dx%d (%dx%d atlas %dx%d), "
               "%u samples/pixel; probes %dx%dx%d (%s), L%d\n",
               a.tag(), s.path.c_str(), s.triangle_count(), gpu.device().info().name.c_str(),
               first.name.c_str(), first.size(), first.layout.tile_width,
               first.layout.tile_height, first.layout.columns, first.layout.rows,
               first.layout.width, first.layout.height, renderer.samples(), grid.counts().x,
               grid.counts().y, grid.counts().z, placement.how.c_str(), renderer.sh_order());

  if (local) {
    const probes::SchedulerOptions& so = local->scheduler.options();
    std::fprintf(stderr, "render: schedule %s, blend %s, max age %u frames, budget %s\n",
                 probes::schedule_mode_name(so.mode), probes::blend_rule_name(so.blend),
                 so.priority.max_age,
                 local->budget_ms > 0.0 ? fmt::format("{:g} ms per frame", local->budget_ms).c_str() : "none");
  }
  std::fprintf(stderr, "%s: left out\n", a.tag());
  scene::RenderPlan plan = scene::make_plan(scene::analyze(s));
  if (empty_probes > 0) plan.left_out.push_back(empty_probes_item(empty_probes, grid));
  for (const std::string& line : left_out_lines(plan, "  "))
    std::fprintf(stderr, "%s\n", line.c_str());

  // The views are rebuilt from the posed scene every frame: an animated camera node moves the
  // whole rig.
  std::unique_ptr<LiveControls> controls;
  if (live)
    controls = std::make_unique<LiveControls>(*live, renderer, volume,
                                              local ? &local->scheduler : nullptr, a.no_indirect, a.tag());
  if (controls && local) controls->set_volume_reader([&local, &volume] { local->engine.read_back(volume); });
  const ViewSource views = [&](const scene::Scene& posed) {
    if (controls) return controls->frame_views(posed, choice, a.display, a.view);
    return make_frame_views(posed, choice, a.display, a.view).views;
  };
  const std::unique_ptr<ProbeSource> probes =
      make_probe_source(local.get(), a.probe, a.schedule, stream, volume, identity, a.tag());
  // Indirect light switched off in the window: no probe updates either (as --no-indirect).
  const bool always = true;
  SwitchableProbes switchable(*probes, controls ? controls->indirect() : always);
  FrameLoop loop(s, switchable, renderer, views);
  FrameLoopOptions options;
  options.frames = live && !a.frames_given ? std::numeric_limits<int>::max() : a.frames;
  const bool files = !live || a.frames_given;
  options.time = a.time;
  options.fps = a.fps;
  options.every = live ? 1 : a.every;  // the window is shown every frame; files as asked
  // Ctrl-C: this frame is the last one, written whole; the window's close does the same.
  options.stop = controls ? &controls->stop() : &stop_flag();
  if (live) options.render_request = live->request(files);
  options.render_request.linear = writes_format(a, "exr");  // only EXRs hold the linear pixels
  // The frames whose files are written: with the window the sink gets every frame (to present
  // it), but only these come back to the CPU (FrameLoopOptions::read_back).
  const auto writes = [&](int k, bool last) {
    return files && ((a.every > 0 && (k + 1) % a.every == 0) || last);
  };
  if (live) options.read_back = writes;
  double present_ms = 0.0;
  options.loop_period = a.loop ? s.animation_duration() : 0.0;
  options.warmup = a.warmup;
  // Without indirect light nothing reads the probes: tracing them would only cost time (and
  // would make a direct-light-only run's frame time meaningless as a baseline).
  options.update_probes = !a.no_indirect;
  if (a.no_indirect) std::fprintf(stderr, "%s: --no-indirect: probes are neither traced nor drawn\n", a.tag());
  // Images are encoded and written by the queue's thread while the next frames are drawn; the
  // loop's "output" stage is the hand-over of the views plus any wait for the writer, and the
  // last frame's "output_drain" the wait for the writer to finish after the loop.
  OutputQueue queue(writer);
  const FrameSink sink = [&](int k, raster::FrameOutput& frame) {
    if (live) {
      present_ms = live->present();
      // A frame read back is one to write (the loop asked `writes` with what it knew).
      if (frame.views.empty() || frame.views.front().display.empty()) return std::vector<fs::path>{};
    }
    const std::string tag = a.every > 0 ? fmt::format("{:04d}", k) : "";
    queue.push(std::move(frame.views), fmt::format("frame_{:04d}", k), tag);
    return std::vector<fs::path>{};
  };
  run.result = loop.run(options, sink, [&](const FrameReport& r) {
    if (r.warmup && r.warmup->rounds > 0)
      std::fprintf(stderr, "%s: %s\n", a.tag(), describe_warmup(*r.warmup, a.warmup).c_str());
    if (remote && r.frame == 0 && r.counts.stream && !r.counts.stream->synced && !a.no_indirect)
      std::fprintf(stderr, "view: no probe server at %s after %d ms: rendering with %s until it answers\n",
                   a.connect.c_str(), a.wait_ms,
                   a.baked.empty() ? "direct light only" : ("the baked probes of " + a.baked).c_str());
    if (timings) timings->add(*r.timings, r.counts);
    print_progress(r, options.frames);
    if (live) live->set_status(controls->status(first.name, r, present_ms));
  });
  const auto drain_start = std::chrono::steady_clock::now();
  run.result.written = queue.finish();
  if (timings && timings->last())
    timings->last()->add(
        "output_drain",
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - drain_start).count());
  if (live) {
    run.window_closed = live->quit();
    if (a.live.hold && !live->quit() && !stop_flag().load()) {
      for (const fs::path& p : run.result.written) std::printf("wrote %s\n", p.string().c_str());
      std::fflush(stdout);
      run.result.written.clear();
      std::fprintf(stderr, "%s: holding frame %zu in the window until it is closed\n", a.tag(),
                   run.result.frames);
      live->hold(stop_flag());
      run.window_closed = live->quit();
    }
  }
  return run;
}

int run_render(const RenderArgs& a) {
  if (a.display.display == "list") {
    std::printf("%s", display_list().c_str());
    return 0;
  }
  check(a);  // before loading: a bad option should not cost a scene load
  const DisplayChoice choice = resolve_display(a.display, a.view);
  // Nor an output that cannot be written.
  io::check_writable_folder(a.out);
  if (!a.timings.empty()) io::check_writable_file(a.timings);
  std::optional<display::Calibration> calibration;
  if (!a.calibration.empty()) calibration = display::load_calibration(a.calibration);
  scene::Scene s = scene::load_scene(a.scene);
  const std::uint64_t geometry = geometry_identity(s);  // before posing moves animated nodes
  s.pose(a.time);
  const std::string framing = frame_camera_less(s, a.view, view_aspect(choice, a.view));
  const std::string environment = apply_lighting(s, a.lighting);
  const display::ViewSet first = make_frame_views(s, choice, a.display, a.view);
  const FrameWriter writer(first, {.dir = a.out,
                                   .stem = fs::path(a.scene).stem().string(),
                                   .per_view = a.per_view,
                                   .calibration = calibration,
                                   .png = writes_format(a, "png"),
                                   .exr = writes_format(a, "exr")});

  // Said once the views and outputs are known to be good: bad input gets its one error line only.
  if (!framing.empty()) std::fprintf(stderr, "%s: %s\n", a.tag(), framing.c_str());
  std::fprintf(stderr, "%s: %s\n", a.tag(), environment.c_str());
  allow_graceful_stop();
  // A client asks its servers first: their grid is its grid. Its wait_ms is then what is left.
  StreamArgs stream = stream_args(a);
  if (!a.connect.empty()) describe_stream(stream, a.tag());
  const Placement placement = a.connect.empty() ? place_probes(a.probe, s) : client_placement(a.probe, s, stream, a.tag());
  std::optional<TimingsFile> timings;
  if (!a.timings.empty()) timings.emplace(a.timings, first);
  const GpuRun run = render_frames(a, s, placement, stream, choice, first, writer,
                                   scene_identity(geometry, placement.grid, a.probe.sh_order),
                                   calibration, timings ? &*timings : nullptr);
  const std::size_t done = run.result.frames;
  if (run.window_closed && stop_signal() == 0)
    std::fprintf(stderr, "%s: window closed after frame %zu\n", a.tag(), done);
  else if (run.result.stopped && a.live.window && !a.frames_given)
    std::fprintf(stderr, "%s: stopped by %s after frame %zu (t=%.3f s); the window writes no files%s\n",
                 a.tag(), stop_signal() == SIGTERM ? "SIGTERM" : "SIGINT", done,
                 a.time + double(done - 1) / a.fps, a.timings.empty() ? "" : ", --timings has the frames done");
  else if (run.result.stopped)
    std::fprintf(stderr, "%s: stopped by %s after frame %zu of %d (t=%.3f s): its images are "
                 "written, %s\n",
                 a.tag(), stop_signal() == SIGTERM ? "SIGTERM" : "SIGINT", done, a.frames,
                 a.time + double(done - 1) / a.fps,
                 a.timings.empty() ? "no later frame was rendered"
                                   : "--timings has the frames done");
  if (timings) timings->finish();
  for (const fs::path& p : run.result.written) std::printf("wrote %s\n", p.string().c_str());
  if (!a.timings.empty()) std::printf("wrote %s\n", a.timings.c_str());
  if (run.validation) {
    const std::uint32_t errors = run.log->errors();
    std::fprintf(stderr, "%s: validation: %u errors, %u warnings\n", a.tag(), errors,
                 run.log->warnings());
    if (errors > 0) {
      const std::vector<std::string> messages = run.log->error_messages();
      std::fprintf(stderr, "ddish: error: Vulkan validation reported %u error%s (first: %s)\n",
                   errors, errors == 1 ? "" : "s",
                   messages.empty() ? "not kept" : messages.front().c_str());
      return 1;
    }
  }
  return run.result.stopped && stop_signal() != 0 ? interrupted_exit_code(stop_signal()) : 0;
}

// The options `ddish render` and `ddish view` share: views, display, frames, output, raster.
void add_frame_options(CLI::App* cmd, RenderArgs& a) {
  // Not required by CLI11: `--display list` needs no scene (check() asks for it otherwise).
  cmd->add_option("scene", a.scene, "glTF 2.0 scene (.gltf or .glb)")->check(CLI::ExistingFile);
  add_camera_options(*cmd, a.view);
  add_display_options(*cmd, a.display);
  cmd->add_flag("--per-view", a.per_view, "also write every view as DIR/view_NN.png and .exr (those of --formats)");
  cmd->add_option("--formats", a.formats,
                  "image files written, comma-separated: png (display values, tone-mapped), exr "
                  "(linear radiance, half floats); a run that writes no EXR reads back no linear "
                  "pixels (6 bytes a pixel less held per frame)")
      ->delimiter(',')
      ->check(CLI::IsMember({"png", "exr"}))
      ->default_str("png,exr");
  cmd->add_option("--calibration", a.calibration,
                  "Looking Glass calibration (visual.json): also write the lenticular panel image")
      ->check(CLI::ExistingFile);
  cmd->add_option("--frames", a.frames,
                  "frames to render (with --window: none given runs until the window is closed "
                  "and writes no files)")
      ->capture_default_str()
      ->each([&a](const std::string&) { a.frames_given = true; });
  cmd->add_flag("--window", a.live.window,
                "show the frames live in a window (SDL2 + Vulkan swapchain): the view, the stereo "
                "pair, the quilt, or with --calibration the lenticular panel image built on the "
                "GPU; mouse: left drag orbit, right/middle drag pan, wheel dolly; keys: WASD QE "
                "fly, I indirect light, U schedule, G probe-grid overlay, H status text, Esc quit");
  cmd->add_option("--monitor", a.live.monitor,
                  "with --window: the monitor (SDL display index, listed in the run log); default: "
                  "the monitor of the profile's panel resolution (a Looking Glass), else 0")
      ->each([&a](const std::string&) { a.monitor_given = true; });
  cmd->add_flag("--fullscreen", a.live.fullscreen,
                "with --window: borderless fullscreen at the monitor's own resolution (the panel's "
                "native resolution on a Looking Glass)");
  cmd->add_flag("--mailbox", a.live.mailbox, "with --window: MAILBOX presentation where offered (else FIFO)");
  cmd->add_flag("--hold", a.live.hold,
                "with --window and --frames: after the last frame keep showing it until the window "
                "is closed (Esc) or the process is signalled");
  cmd->add_flag("--no-status", a.live.no_status,
                "with --window: start with the status text (probes / raster / present ms, views, "
                "probe age, switches; top-left, on a lenticular panel in every view) hidden; H "
                "shows it");
  cmd->add_flag("--every{1}", a.every,
                "--every: write every frame, not only the last; --every=N: every N-th frame "
                "(frames N-1, 2N-1, ...) and the last (only the frames written are read back "
                "from the GPU)")
      ->check(CLI::Range(1, 1000000));
  cmd->add_flag("--loop", a.loop,
                "play the animations again and again: the scene time wraps at the longest "
                "animation's duration (without it the last pose holds)");
  cmd->add_option("--fps", a.fps, "frame k shows the scene at time + k / fps")->capture_default_str();
  cmd->add_option("--time", a.time, "scene time of frame 0 (seconds)")->capture_default_str();
  cmd->add_option("--out", a.out, "output directory")->capture_default_str();
  cmd->add_option("--timings", a.timings, "write per-frame stage milliseconds as JSON here");
  add_raster_options(*cmd, a.raster);
  cmd->add_option("--tonemap", a.tonemap, "display curve of the PNG: linear or filmic (ACES fit)")
      ->capture_default_str();
  cmd->add_flag("--no-indirect", a.no_indirect,
                "direct light only: the probes are neither traced nor drawn");
  RenderArgs* args = &a;
  cmd->add_option_function<std::uint32_t>(
      "--device", [args](std::uint32_t d) { args->device = d; }, "Vulkan device index (see ddish devices)");
}

Action make_render(CLI::App& root) {
  auto a = std::make_shared<RenderArgs>();
  CLI::App* cmd = root.add_subcommand(
      "render", "the main job: probes updated and views rasterized per frame, written to --out");
  add_frame_options(cmd, *a);
  add_probe_options(*cmd, a->probe);
  add_visibility_options(*cmd, a->probe);
  add_lighting_options(*cmd, a->lighting, /*exposure=*/true);
  add_schedule_options(*cmd, a->schedule);
  add_warmup_options(*cmd, a->warmup);
  add_tracer_option(*cmd, a->tracer);
  add_probe_readback_option(*cmd, a->probe_readback);
  return [a]() { return run_render(*a); };
}

Action make_view(CLI::App& root) {
  auto a = std::make_shared<RenderArgs>();
  CLI::App* cmd = root.add_subcommand(
      "view", "ddish render with the probes of a ddish serve: views rasterized, probes streamed");
  add_frame_options(cmd, *a);
  cmd->add_option("--connect", a->connect,
                  "the probe server, tcp://HOST:PORT (PORT+1 is its request socket); several servers "
                  "of one scene (serve --bricks I/N), comma-separated")
      ->required();
  cmd->add_option("--relay", a->relay, "take the probe frames through this ddish relay (tcp://HOST:PORT); "
                  "snapshots and views still go to each --connect server");
  cmd->add_option("--probes", a->baked,
                  "baked probes (ddish probes --out) to render with until the server answers")
      ->check(CLI::ExistingFile);
  cmd->add_option("--wait-ms", a->wait_ms,
                  "how long the client waits in all for the servers' stream description (its grid bounds and moment maps) and "
                  "then, with what is left, the first frame for their snapshot")
      ->capture_default_str();
  cmd->add_option("--frame-wait-ms", a->frame_wait_ms,
                  "each later frame waits up to this long for the server's next frame (0: takes what arrived)")
      ->capture_default_str();
  cmd->add_option("--stale-ms", a->stale_ms, "no message from the server for this long while connected: say it is slow (a dropped connection is a lost server)")
      ->capture_default_str();
  cmd->add_option("--curve-server-key", a->curve_server_key, "the server's public key (.pub): CurveZMQ on")
      ->check(CLI::ExistingFile);
  cmd->add_option("--curve-secret", a->curve_secret, "this client's secret key (.key of ddish keys)")
      ->check(CLI::ExistingFile);
  // The probe counts must be the server's (the scene identity covers the grid); the bounds come
  // from the server's stream description where it gives them.
  cmd->add_option("--grid", a->probe.grid,
                  "probe counts X,Y,Z, or auto, as the server's (default: sidecar counts, else automatic)");
  cmd->add_option("--probe-spacing", a->probe.spacing, "as the server's --probe-spacing");
  cmd->add_option("--probe-placement", a->probe.placement,
                  "as the server's --probe-placement, for a server that does not describe its grid's bounds at "
                  "start (a server that does moves this client's grid to its own)")
      ->check(CLI::IsMember({"centres", "fit"}))
      ->capture_default_str();
  cmd->add_option("--sh-order", a->probe.sh_order, "as the server's --sh-order")->capture_default_str();
  // The sky or environment map the view draws behind the scene: give the server's (serve --sky,
  // --environment), so that the background matches the light in the probes.
  add_lighting_options(*cmd, a->lighting, /*exposure=*/true);
  return [a]() { return run_render(*a); };
}

}  // namespace

DDISH_COMMAND(20, make_render);
DDISH_COMMAND(61, make_view);

}  // namespace ddish::app
