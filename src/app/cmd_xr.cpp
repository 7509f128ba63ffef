// ddish xr SCENE [--connect tcp://HOST:PORT [--probes FILE] [--wait-ms MS] ...] [--frames N]
//                [--camera NODE|eye,target,up] [--tracer auto|embree|vulkan] [probe, schedule, lighting and raster options]
//                [--warmup-ms MS] [--warmup-samples N] [--timings FILE]
//
// Stereo through OpenXR: the system loader's runtime (XR_RUNTIME_JSON, else the active runtime)
// creates the Vulkan instance and device (XR_KHR_vulkan_enable2), the session runs its state
// machine, and each frame the located eyes are rendered by the same frame loop as `render`, with
// the probes in-process (the scheduler's budget is the runtime's display period less the
// measured rest of the frame) or streamed from a `ddish serve` (--connect, as `ddish view`). The
// views are copied on the GPU into the swapchain images. The headset's LOCAL space sits at the
// scene's camera (--camera, else the scene's or the framing camera): its origin at the camera's
// eye, looking along its forward. Runs until the runtime ends the session, or --frames N
// rendered frames (then it asks the runtime to end). With DDISH_VALIDATION=1 the OpenXR core
// validation layer and the Vulkan validation layer are on; any message of either exits 1.
// No runtime: one line naming XR_RUNTIME_JSON and active_runtime.json, exit 2. A lost session
// (LOSS_PENDING): everything is destroyed, one line, exit 1.
#include <algorithm>
#include <climits>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "app/camera_options.h"
#include "app/commands.h"
#include "app/frame_loop.h"
#include "app/interrupt.h"
#include "app/lighting_options.h"
#include "app/probe_options.h"
#include "app/probe_setup.h"
#include "app/option_checks.h"
#include "app/render_timings.h"
#include "app/scene_identity.h"
#include "app/schedule_options.h"
#include "app/tracer_choice.h"
#include "app/warmup_options.h"
#include "app/xr_frames.h"
#include "display/view_set.h"
#include "gpu/context.h"
#include "io/atomic_file.h"
#include "net/endpoint.h"
#include "raster/renderer.h"
#include "raster/tonemap.h"
#include "scene/gltf_loader.h"
#include "scene/scene.h"
#include "xr/instance.h"
#include "xr/session.h"
#include "xr/vulkan_binding.h"

namespace ddish::app {
namespace {

struct XrArgs {
  std::string scene;
  CameraArgs view;
  ProbeArgs probe;
  ScheduleArgs schedule;
  LightingArgs lighting;
  StreamArgs stream;
  WarmupOptions warmup;
  int frames = 0;  // 0: until the runtime ends the session
  std::string timings;
  std::uint32_t msaa = 0;
  std::string tonemap = "filmic";
  bool no_indirect = false;
  std::string tracer = "auto";  // --tracer, for in-process probes
  bool probe_readback = false;  // --probe-readback: no GPU-resident hand-off
};

void check(const XrArgs& a) {
  check_frame_options(a.probe, a.schedule, a.warmup, a.lighting, a.view, a.tonemap);
  if (a.frames < 0) throw std::invalid_argument("--frames must be >= 0 (0: until the runtime ends the session)");
  if (!a.stream.connect.empty()) net::parse_endpoint_list(a.stream.connect);
  if (a.stream.curve_server_key.empty() != a.stream.curve_secret.empty())
    throw std::invalid_argument("--curve-server-key and --curve-secret go together");
  if (a.msaa != 0 && a.msaa != 1 && a.msaa != 2 && a.msaa != 4 && a.msaa != 8 && a.msaa != 16)
    throw std::invalid_argument(fmt::format("--msaa must be 1, 2, 4, 8 or 16, got {}", a.msaa));
}

struct XrRun {
  FrameLoopResult result;
  XrFrameTally tally;
  bool lost = false;
  std::uint32_t xr_messages = 0;
  bool validation = false;
  std::shared_ptr<const gpu::ValidationLog> vulkan_log;
  int eye_width = 0, eye_height = 0;
  std::vector<std::string> states;
};

// Everything with OpenXR or Vulkan handles lives in here, destroyed in order before it returns.
// The --timings file's views: the two eyes side by side.
display::ViewSet eye_set(int width, int height) {
  display::ViewSet set;
  set.kind = display::ViewSetKind::Stereo;
  set.name = "openxr";
  set.layout = display::layout_from_tiles(2, 1, width, height);
  return set;
}

XrRun run_session(const XrArgs& a, scene::Scene& s, const Placement& placement, const StreamArgs& stream,
                  std::uint64_t identity,
                  std::optional<TimingsFile>& timings) {
  XrRun run;
  const bool remote = !a.stream.connect.empty();
  // Decided on the default device before the runtime starts, so a tracer that cannot run is one
  // error line; checked again on the device the runtime picks.
  std::optional<TracerDecision> tracer;
  if (!remote) tracer = choose_tracer(a.tracer, std::nullopt);
  const bool validation = gpu::validation_requested_by_environment();
  xr::Instance xri({.application_name = "ddish", .validation = validation});
  const auto eyes = xri.recommended();
  if (eyes[0].width != eyes[1].width || eyes[0].height != eyes[1].height)
    throw std::runtime_error(fmt::format("xr: the eyes' recommended sizes differ ({}x{}, {}x{})", eyes[0].width,
                                         eyes[0].height, eyes[1].width, eyes[1].height));
  run.eye_width = static_cast<int>(eyes[0].width);
  run.eye_height = static_cast<int>(eyes[0].height);
  if (!a.timings.empty()) timings.emplace(a.timings, eye_set(run.eye_width, run.eye_height));
  std::fprintf(stderr, "xr: runtime %s, system %s, eyes %ux%u%s\n", xri.runtime_name().c_str(),
               xri.system_name().c_str(), eyes[0].width, eyes[0].height,
               xri.validation_enabled() ? ", OpenXR core validation on" : "");

  probes::ProbeVolume volume = remote ? starting_volume(a.probe, stream, placement, "xr")
                                      : local_volume(a.probe, placement.grid);
  if (!remote) {
    const std::uint32_t n = leave_out_empty_probes(volume, s);
    if (n > 0) {
      const scene::PlanItem item = empty_probes_item(n, volume.grid());
      std::fprintf(stderr, "xr: left out %s: %s\n", item.what.c_str(), item.why.c_str());
    }
  }
  {
    gpu::ContextOptions co;
    co.validation = validation;
    // The GPU probe tracer shares the runtime's device, with ray tracing switched on for it.
    co.ray_tracing = tracer && tracer->kind == TracerKind::vulkan;
    xr::bind_vulkan(xri, co);
    gpu::Context gpu(co);
    if (co.ray_tracing && !gpu.device().features().ray_tracing) {
      const std::string device = gpu.device().info().name;
      if (a.tracer == "vulkan")
        throw std::invalid_argument("--tracer vulkan: the OpenXR runtime's device " + device +
                                    " has no Vulkan ray-tracing pipelines");
      tracer = TracerDecision{TracerKind::embree, "embree (auto: the runtime's device " + device +
                                                      " has no ray-tracing pipelines)"};
    }
    if (tracer) std::fprintf(stderr, "xr: probe tracer %s\n", tracer->why.c_str());
    // The in-process probe parts hold Vulkan objects when they trace on the GPU: made after the
    // context, destroyed before it. The budget comes from the runtime each frame; --budget-ms
    // fixes it instead (0: none).
    std::unique_ptr<InProcessParts> local;
    if (tracer)
      local = make_in_process(a.probe, a.schedule, s, a.schedule.budget_ms.value_or(0.0), tracer->kind, std::nullopt,
                              tracer->kind == TracerKind::vulkan ? &gpu.device() : nullptr);
    // The GPU tracer shares the runtime's device: its probes go to the rasterizer on the GPU.
    if (local && local->engine.keep_probes_on_device(!a.probe_readback))
      std::fprintf(stderr, "xr: traced probes stay on the GPU (converted there for the rasterizer)\n");
    run.validation = gpu.instance().validation_enabled();
    run.vulkan_log = gpu.instance().shared_validation();
    raster::RendererOptions ro;
    ro.msaa = a.msaa;
    ro.tone_curve = raster::parse_tone_curve(a.tonemap);
    ro.exposure = exposure_scale(a.lighting);
    ro.probes = !a.no_indirect;
    raster::Renderer renderer(gpu.device(), s, volume, ro);
    std::fprintf(stderr, "xr: %s, %zu triangles on %s; probes %dx%dx%d (%s), L%d, %u samples/pixel\n",
                 s.path.c_str(), s.triangle_count(), gpu.device().info().name.c_str(), placement.grid.counts().x,
                 placement.grid.counts().y, placement.grid.counts().z, placement.how.c_str(), renderer.sh_order(),
                 renderer.samples());
    const std::unique_ptr<ProbeSource> probes =
        make_probe_source(local.get(), a.probe, a.schedule, stream, volume, identity, "xr");

    xr::Session session(xri, gpu.device());
    const scene::Camera camera = resolve_camera(s, a.view);
    const display::BaseCamera origin =
        display::base_camera(camera, display::focal_distance_to_scene_center(s, camera.eye, camera.forward));
    XrFrames frames(session, origin, a.schedule.budget_ms);

    FrameLoop loop(s, *probes, renderer, [&](const scene::Scene&) { return frames.views(); });
    FrameLoopOptions options;
    options.frames = a.frames > 0 ? a.frames : INT_MAX;
    options.fps = 90.0;  // scene time advances 1/90 s a frame
    options.every = 1;  // every frame goes to the headset
    options.stop = &stop_flag();
    options.update_probes = !a.no_indirect;
    options.warmup = a.warmup;
    options.render_request.read_back = false;
    options.render_request.after_batch = [&](VkCommandBuffer cmd, const raster::BatchViews& b) { frames.after_batch(cmd, b); };
    options.pacer = [&](int k) { return frames.pace(k); };
    const FrameSink sink = [&](int k, raster::FrameOutput&) {
      frames.submit(k);
      return std::vector<std::filesystem::path>{};
    };
    run.result = loop.run(options, sink, [&](const FrameReport& r) {
      if (r.warmup && r.warmup->rounds > 0) std::fprintf(stderr, "xr: %s\n", describe_warmup(*r.warmup, a.warmup).c_str());
      const XrFrameRecord& x = frames.last();
      if (timings) timings->add(*r.timings, r.counts, {{"xr", xr_record_json(x)}});
      std::fprintf(stderr,
                   "frame %d: probes %.1f ms (%u traced at %u samples), raster %.1f ms, frame %.1f ms of period "
                   "%.2f ms (budget %.2f ms), pose to submit %.1f ms, waited %.1f ms%s\n",
                   r.frame + 1, r.timings->stage_ms("probe_update"), r.counts.probes_traced,
                   r.counts.schedule.samples_per_probe, raster_ms(*r.timings), x.frame_ms, x.period_ms, x.budget_ms,
                   x.pose_to_submit_ms, x.wait_ms, x.skipped_before ? fmt::format(", {} not rendered before", x.skipped_before).c_str() : "");
    });
    if (!session.lost()) frames.finish();
    run.lost = session.lost();
    run.tally = frames.tally();
    run.states = session.states();
    gpu.device().wait_idle();
  }  // session, renderer, device, Vulkan instance: gone before the OpenXR instance
  run.xr_messages = xri.validation_messages();
  return run;
}


int run_xr(const XrArgs& a) {
  check(a);
  if (!a.timings.empty()) io::check_writable_file(a.timings);
  scene::Scene s = scene::load_scene(a.scene);
  const std::uint64_t geometry = geometry_identity(s);
  s.pose(0.0);
  const std::string framing = frame_camera_less(s, a.view, 0.9f);
  const std::string environment = apply_lighting(s, a.lighting);
  if (!framing.empty()) std::fprintf(stderr, "xr: %s\n", framing.c_str());
  std::fprintf(stderr, "xr: %s\n", environment.c_str());
  allow_graceful_stop();
  // A client asks its servers first: their grid is its grid. Its wait_ms is then what is left.
  StreamArgs stream = a.stream;
  if (!stream.connect.empty()) describe_stream(stream, "xr");
  const Placement placement = stream.connect.empty() ? place_probes(a.probe, s) : client_placement(a.probe, s, stream, "xr");
  std::optional<TimingsFile> timings;
  const XrRun run =
      run_session(a, s, placement, stream, scene_identity(geometry, placement.grid, a.probe.sh_order), timings);

  std::string states;
  for (const std::string& st : run.states) states += (states.empty() ? "" : " ") + st;
  std::fprintf(stderr, "xr: %zu frames rendered, %zu within the display period; pose to submit median %.1f ms; session %s\n",
               static_cast<std::size_t>(run.tally.rendered), static_cast<std::size_t>(run.tally.within_period),
               run.tally.median_latency_ms(), states.c_str());
  if (timings) {
    timings->finish();
    std::printf("wrote %s\n", a.timings.c_str());
  }
  int code = 0;
  if (run.validation || run.xr_messages > 0) {
    const std::uint32_t vk = run.vulkan_log ? run.vulkan_log->errors() : 0;
    std::fprintf(stderr, "xr: validation: %u OpenXR messages, %u Vulkan errors, %u Vulkan warnings\n", run.xr_messages,
                 vk, run.vulkan_log ? run.vulkan_log->warnings() : 0);
    if (vk > 0 || run.xr_messages > 0) {
      std::fprintf(stderr, "ddish: error: validation reported %u OpenXR and %u Vulkan messages\n", run.xr_messages, vk);
      code = 1;
    }
  }
  if (run.lost) {
    std::fprintf(stderr, "ddish: error: xr: the runtime lost the session (LOSS_PENDING) after %d frames\n", run.tally.rendered);
    return 1;
  }
  if (run.result.stopped) return interrupted_exit_code(stop_signal());
  return code;
}

Action make_xr(CLI::App& root) {
  auto a = std::make_shared<XrArgs>();
  CLI::App* cmd = root.add_subcommand("xr", "stereo through OpenXR: the runtime's eyes, poses and frame timing");
  cmd->add_option("scene", a->scene, "glTF 2.0 scene (.gltf or .glb)")->required()->check(CLI::ExistingFile);
  cmd->add_option("--camera", a->view.camera,
                  "where the headset's LOCAL space sits: a camera NODE or eye,target,up (default: the scene's camera)");
  cmd->add_option("--frames", a->frames, "rendered frames, then the session ends; 0: until the runtime ends it")
      ->capture_default_str();
  cmd->add_option("--timings", a->timings, "write per-frame stage milliseconds and the OpenXR frame records as JSON here");
  cmd->add_option("--msaa", a->msaa, "samples per pixel (default: 4 where supported, else 1)");
  cmd->add_option("--tonemap", a->tonemap, "display curve: linear or filmic (ACES fit)")->capture_default_str();
  cmd->add_flag("--no-indirect", a->no_indirect, "direct light only: the probes are neither traced nor drawn");
  cmd->add_option("--connect", a->stream.connect,
                  "probes from a ddish serve at tcp://HOST:PORT (as ddish view) instead of in-process");
  cmd->add_option("--probes", a->stream.baked, "with --connect: baked probes (ddish probes --out) until the server answers")
      ->check(CLI::ExistingFile);
  cmd->add_option("--wait-ms", a->stream.wait_ms, "with --connect: the wait in all for the servers' stream description (its grid bounds and moment maps) and then, with what is left, the first frame's for their snapshot")
      ->capture_default_str();
  cmd->add_option("--frame-wait-ms", a->stream.frame_wait_ms, "with --connect: each later frame's wait for the server")
      ->capture_default_str();
  cmd->add_option("--stale-ms", a->stream.stale_ms, "with --connect: no message for this long while connected: say the server is slow (a dropped connection is a lost server)")
      ->capture_default_str();
  cmd->add_option("--curve-server-key", a->stream.curve_server_key, "with --connect: the server's public key (.pub)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--curve-secret", a->stream.curve_secret, "with --connect: this client's secret key (.key)")
      ->check(CLI::ExistingFile);
  add_probe_options(*cmd, a->probe);
  add_visibility_options(*cmd, a->probe);
  add_tracer_option(*cmd, a->tracer);
  add_probe_readback_option(*cmd, a->probe_readback);
  add_lighting_options(*cmd, a->lighting, /*exposure=*/true);
  add_schedule_options(*cmd, a->schedule);
  cmd->get_option("--budget-ms")
      ->description("whole-frame time budget in ms (default: each frame's predicted display period from the runtime; 0: none)");
  add_warmup_options(*cmd, a->warmup);
  return [a]() { return run_xr(*a); };
}

}  // namespace

DDISH_COMMAND(65, make_xr);

}  // namespace ddish::app
