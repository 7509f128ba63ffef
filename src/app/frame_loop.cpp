#include "app/frame_loop.h"

#include <algorithm>
#include <cmath>

#include "probes/probe_volume.h"
#include "raster/renderer.h"
#include "scene/scene.h"
#include "trace/tracer.h"

namespace ddish::app {

FrameLoop::FrameLoop(scene::Scene& scene, ProbeSource& probes, raster::Renderer& renderer,
                     ViewSource views)
    : scene_(scene), probes_(probes), renderer_(renderer), views_(std::move(views)) {}

FrameLoop::FrameLoop(scene::Scene& scene, ProbeEngine& engine, probes::Scheduler& scheduler,
                     UpdateOptionsFor update_options, probes::ProbeVolume& volume,
                     raster::Renderer& renderer, ViewSource views)
    : scene_(scene),
      owned_probes_(std::make_unique<InProcessProbes>(engine, scheduler,
                                                      std::move(update_options), volume)),
      probes_(*owned_probes_),
      renderer_(renderer),
      views_(std::move(views)) {}

namespace {

// The volume's probes after this frame's update: active, inactive, never updated, oldest.
void count_probes(const probes::ProbeVolume& volume, FrameCounts& counts) {
  for (std::uint32_t i = 0; i < volume.probe_count(); ++i) {
    const probes::ProbeState& s = volume.state(i);
    if (s.unclassified()) ++counts.probes_unclassified;
    if (s.inside_geometry()) ++counts.probes_inside_geometry;
    if (!s.active()) {
      ++counts.probes_inactive;
      continue;
    }
    ++counts.probes_active;
    if (s.updates == 0) ++counts.probes_never_updated;
    counts.oldest_probe_age = std::max(counts.oldest_probe_age, s.age);
  }
}

// The changed probes to the renderer: converted on the device from the probe tracer's averages
// where the source keeps them there (no CPU copy), else uploaded from the volume.
raster::ProbeUploadStats hand_off(ProbeSource& source, raster::Renderer& renderer,
                                  const std::vector<std::uint32_t>& changed) {
  if (const std::optional<raster::GpuProbeData> gpu = source.gpu_probes())
    return renderer.import_probes(source.volume(), *gpu, changed);
  return renderer.upload_probes(source.volume(), changed);
}

// A render's stages and passes into the frame's (a frame rendered again counts both). The GPU
// passes run while the CPU waits for the submission, so the wait is split into the passes'
// timestamp durations and the rest (submission, resolve and copies, idle): the stages of a
// frame add up to its wall time.
void add_raster(const raster::FrameStats& st, metrics::FrameTimings& timings, FrameCounts& counts) {
  const double gpu_ms = st.shadow_gpu_ms + st.forward_gpu_ms + st.tonemap_gpu_ms;
  timings.add("raster_record", st.record_ms);
  timings.add("shadow_gpu", st.shadow_gpu_ms);
  timings.add("forward_gpu", st.forward_gpu_ms);
  timings.add("tonemap_gpu", st.tonemap_gpu_ms);
  timings.add("raster_wait", std::max(0.0, st.execute_ms - gpu_ms));
  timings.add("readback", st.readback_ms);
  counts.shadow_passes += st.shadow_passes;
  if (!counts.rendered_again) counts.shadows_reused = st.shadows_reused;  // the frame's first render
  counts.forward_passes += st.forward_passes;
  counts.tonemap_passes += st.tonemap_passes;
}

}  // namespace

FrameLoopResult FrameLoop::run(const FrameLoopOptions& o, const FrameSink& sink,
                               const std::function<void(const FrameReport&)>& progress) {
  FrameLoopResult result;
  // Whether frame k (the run's last when `last`) needs its pixels on the CPU: the sink gets it
  // and writes it.
  const auto wants_pixels = [&](int k, bool last) {
    const bool taken = sink && ((o.every > 0 && (k + 1) % o.every == 0) || last);
    return o.render_request.read_back && taken && (!o.read_back || o.read_back(k, last));
  };
  if (o.warmup.enabled() && o.update_probes) {
    metrics::FrameTimings ignored;  // the warm-up is no frame's stage
    const double t0 = o.loop_period > 0.0 ? std::fmod(o.time, o.loop_period) : o.time;
    probes_.posed(scene_, scene_.pose(t0), ignored);
    result.warmup = probes_.warm_up(o.warmup);
    if (!result.warmup.changed.empty()) hand_off(probes_, renderer_, result.warmup.changed);
  }
  for (int k = 0; k < o.frames; ++k) {
    if (o.pacer) {
      const FrameStart start = o.pacer(k);
      if (start.end) {
        result.paced_out = true;
        break;
      }
      if (start.budget_ms) probes_.set_frame_budget(*start.budget_ms);
    }
    metrics::FrameTimings timings;
    timings.frame = k;
    const double clock = o.time + double(k) / o.fps;
    const double t = o.loop_period > 0.0 ? std::fmod(clock, o.loop_period) : clock;
    FrameReport report;
    report.frame = k;
    report.t = t;
    std::vector<int> moved;
    {
      metrics::StageTimer timer(timings, "pose");
      moved = scene_.pose(t);
    }
    probes_.posed(scene_, moved, timings);
    // The views come first: the scheduler ranks the probes by what they see.
    const std::vector<scene::View> views = views_(scene_);
    report.counts.views = static_cast<std::uint32_t>(views.size());
    const ProbeStep step = probes_.update(views, o.update_probes, timings, report.counts);
    count_probes(probes_.volume(), report.counts);
    {
      metrics::StageTimer timer(timings, "upload");
      report.counts.probes_changed = static_cast<std::uint32_t>(step.changed.size());
      if (!step.changed.empty()) {
        const raster::ProbeUploadStats sent = hand_off(probes_, renderer_, step.changed);
        (sent.imported ? report.counts.probes_imported : report.counts.probes_uploaded) = sent.probes;
      }
    }
    // Only the frames the sink writes are read back; the stop flag is read before the render
    // (a stop already raised makes this frame the last) and again after it.
    const bool stop_before = o.stop && o.stop->load();
    raster::RenderRequest request = o.render_request;
    request.read_back = wants_pixels(k, k + 1 == o.frames || stop_before);
    raster::FrameOutput frame = renderer_.render(scene_, views, request);
    add_raster(frame.stats, timings, report.counts);
    const bool stopping = o.stop && o.stop->load();
    const bool last = k + 1 == o.frames || stopping;
    if (!request.read_back && wants_pixels(k, last)) {
      // The stop came while the frame rendered unread, and the last frame must be written: the
      // same views again (the probes and pose are unchanged), this time read back.
      request.read_back = true;
      report.counts.rendered_again = true;
      frame = renderer_.render(scene_, views, request);
      add_raster(frame.stats, timings, report.counts);
    }
    report.counts.read_back = request.read_back;
    if (sink && ((o.every > 0 && (k + 1) % o.every == 0) || last)) {
      metrics::StageTimer timer(timings, "output");
      for (auto& path : sink(k, frame)) result.written.push_back(std::move(path));
    }
    probes_.finished(k, timings, step, o.update_probes, report.counts);
    // The tracer's worker threads allocate and free every frame in their own malloc arenas,
    // whose free space glibc does not give back by itself: a long run's resident memory crept
    // up by ~1.5 KB a frame with a flat heap (heaptrack) until the free pages were returned.
    if ((k + 1) % kTrimInterval == 0) return_free_memory();
    report.counts.resources = sample_process_resources();
    ++result.frames;
    report.timings = &timings;
    if (k == 0) report.warmup = &result.warmup;
    if (progress) progress(report);
    if (stopping) {
      result.stopped = k + 1 < o.frames;
      break;
    }
  }
  return result;
}

}  // namespace ddish::app
