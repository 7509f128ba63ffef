#include "app/frame_loop.h"

#include <algorithm>

#include "probes/probe_tracer.h"
#include "probes/probe_volume.h"
#include "raster/renderer.h"
#include "scene/scene.h"
#include "trace/tracer.h"

namespace ddish::app {

FrameLoop::FrameLoop(scene::Scene& scene, trace::Tracer& tracer,
                     const probes::ProbeTracer& probe_tracer, probes::ProbeVolume& volume,
                     raster::Renderer& renderer, ViewSource views)
    : scene_(scene),
      tracer_(tracer),
      probe_tracer_(probe_tracer),
      volume_(volume),
      renderer_(renderer),
      views_(std::move(views)) {
  last_flags_.resize(volume.probe_count());
  for (std::uint32_t i = 0; i < volume.probe_count(); ++i) last_flags_[i] = volume.state(i).flags;
}

std::vector<std::uint32_t> FrameLoop::changed_probes() {
  // Updated this frame (age back to 0), or whose flags changed (a probe found inside
  // geometry drops out of the interpolation and must be re-sent with weight 0).
  std::vector<std::uint32_t> dirty;
  for (std::uint32_t i = 0; i < volume_.probe_count(); ++i) {
    const probes::ProbeState& s = volume_.state(i);
    if ((s.active() && s.age == 0) || s.flags != last_flags_[i]) dirty.push_back(i);
    last_flags_[i] = s.flags;
  }
  return dirty;
}

FrameLoopResult FrameLoop::run(const FrameLoopOptions& o, const FrameSink& sink,
                               const std::function<void(const FrameReport&)>& progress) {
  FrameLoopResult result;
  const bool animated = !scene_.animations.empty();
  for (int k = 0; k < o.frames; ++k) {
    metrics::FrameTimings timings;
    timings.frame = k;
    const double t = o.time + double(k) / o.fps;
    FrameReport report;
    report.frame = k;
    report.t = t;
    std::vector<int> moved;
    {
      metrics::StageTimer timer(timings, "pose");
      moved = scene_.pose(t);
    }
    if (animated) {  // lights may move without any instance moving
      metrics::StageTimer timer(timings, "tracer_update");
      tracer_.update(scene_, moved);
    }
    const std::uint64_t updates_before = volume_.frame();
    const std::uint64_t rays_before = tracer_.rays_traced();
    if (o.update_probes) {
      metrics::StageTimer timer(timings, "probe_update");
      report.counts.probes_traced = probe_tracer_.update(volume_).probes_traced;
    }
    report.counts.probe_updates = volume_.frame() - updates_before;
    report.counts.probe_rays = tracer_.rays_traced() - rays_before;
    {
      metrics::StageTimer timer(timings, "upload");
      const std::vector<std::uint32_t> dirty = changed_probes();
      report.counts.probes_uploaded = renderer_.upload_probes(volume_, dirty).probes;
    }
    const std::vector<scene::View> views = views_(scene_);
    report.counts.views = static_cast<std::uint32_t>(views.size());
    const raster::FrameOutput frame = renderer_.render(scene_, views);
    // The GPU passes run while the CPU waits for the submission, so the wait is split into the
    // passes' timestamp durations and the rest (submission, resolve and copies, idle): the
    // stages of a frame add up to its wall time.
    const raster::FrameStats& st = frame.stats;
    const double gpu_ms = st.shadow_gpu_ms + st.forward_gpu_ms + st.tonemap_gpu_ms;
    timings.add("raster_record", st.record_ms);
    timings.add("shadow_gpu", st.shadow_gpu_ms);
    timings.add("forward_gpu", st.forward_gpu_ms);
    timings.add("tonemap_gpu", st.tonemap_gpu_ms);
    timings.add("raster_wait", std::max(0.0, st.execute_ms - gpu_ms));
    timings.add("readback", st.readback_ms);
    const bool last = k + 1 == o.frames;
    if (sink && (o.every || last)) {
      metrics::StageTimer timer(timings, "output");
      for (auto& path : sink(k, frame)) result.written.push_back(std::move(path));
    }
    result.timings.add(timings);
    result.counts.push_back(report.counts);
    report.timings = &result.timings.frames().back();
    if (progress) progress(report);
  }
  return result;
}

}  // namespace ddish::app
