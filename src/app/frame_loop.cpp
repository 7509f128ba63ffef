#include "app/frame_loop.h"

#include <algorithm>
#include <cmath>

#include "probes/probe_volume.h"
#include "raster/renderer.h"
#include "scene/scene.h"
#include "trace/tracer.h"

namespace ddish::app {

FrameLoop::FrameLoop(scene::Scene& scene, trace::Tracer& tracer,
                     probes::ProbeTracer& probe_tracer, probes::Scheduler& scheduler,
                     UpdateOptionsFor update_options, probes::ProbeVolume& volume,
                     raster::Renderer& renderer, ViewSource views)
    : scene_(scene),
      tracer_(tracer),
      probe_tracer_(probe_tracer),
      scheduler_(scheduler),
      update_options_(std::move(update_options)),
      volume_(volume),
      renderer_(renderer),
      views_(std::move(views)) {
  last_flags_.resize(volume.probe_count());
  for (std::uint32_t i = 0; i < volume.probe_count(); ++i) last_flags_[i] = volume.state(i).flags;
}

std::vector<std::uint32_t> FrameLoop::changed_probes(const std::vector<std::uint32_t>& traced) {
  // Traced this frame and still active, or with changed flags (a probe found inside geometry
  // drops out of the interpolation and must be re-sent once with weight 0). Nothing else: an
  // inactive probe is never uploaded again, an untraced active one still holds what was sent.
  std::vector<std::uint32_t> dirty;
  auto next = traced.begin();
  for (std::uint32_t i = 0; i < volume_.probe_count(); ++i) {
    const probes::ProbeState& s = volume_.state(i);
    while (next != traced.end() && *next < i) ++next;
    const bool was_traced = next != traced.end() && *next == i;
    if ((was_traced && s.active()) || s.flags != last_flags_[i]) dirty.push_back(i);
    last_flags_[i] = s.flags;
  }
  return dirty;
}

namespace {

// The volume's probes after this frame's update: active, inactive, never updated, oldest.
void count_probes(const probes::ProbeVolume& volume, FrameCounts& counts) {
  for (std::uint32_t i = 0; i < volume.probe_count(); ++i) {
    const probes::ProbeState& s = volume.state(i);
    if (s.unclassified()) ++counts.probes_unclassified;
    if (!s.active()) {
      ++counts.probes_inactive;
      continue;
    }
    ++counts.probes_active;
    if (s.updates == 0) ++counts.probes_never_updated;
    counts.oldest_probe_age = std::max(counts.oldest_probe_age, s.age);
  }
}

}  // namespace

FrameLoopResult FrameLoop::run(const FrameLoopOptions& o, const FrameSink& sink,
                               const std::function<void(const FrameReport&)>& progress) {
  FrameLoopResult result;
  const bool animated = !scene_.animations.empty();
  for (int k = 0; k < o.frames; ++k) {
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
    if (animated) {  // lights may move without any instance moving
      metrics::StageTimer timer(timings, "tracer_update");
      tracer_.update(scene_, moved);
    }
    // The views come first: the scheduler ranks the probes by what they see.
    const std::vector<scene::View> views = views_(scene_);
    report.counts.views = static_cast<std::uint32_t>(views.size());
    const std::uint64_t updates_before = volume_.frame();
    const std::uint64_t rays_before = tracer_.rays_traced();
    probes::FramePlan plan;
    probes::UpdateStats update;
    if (o.update_probes) {
      metrics::StageTimer timer(timings, "probe_update");
      plan = scheduler_.plan(volume_, views);
      probe_tracer_.set_options(update_options_(plan));
      update = probe_tracer_.update(volume_, plan.probes);  // the frame's one probe update
      report.counts.probes_traced = update.probes_traced;
    }
    report.counts.probe_updates = volume_.frame() - updates_before;
    report.counts.probe_rays = tracer_.rays_traced() - rays_before;
    count_probes(volume_, report.counts);
    {
      metrics::StageTimer timer(timings, "upload");
      const std::vector<std::uint32_t> dirty = changed_probes(plan.probes);
      report.counts.probes_changed = static_cast<std::uint32_t>(dirty.size());
      report.counts.probes_uploaded =
          dirty.empty() ? 0u : renderer_.upload_probes(volume_, dirty).probes;
    }
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
    report.counts.shadow_passes = st.shadow_passes;
    report.counts.shadows_reused = st.shadows_reused;
    report.counts.forward_passes = st.forward_passes;
    report.counts.tonemap_passes = st.tonemap_passes;
    const bool last = k + 1 == o.frames;
    if (sink && (o.every || last)) {
      metrics::StageTimer timer(timings, "output");
      for (auto& path : sink(k, frame)) result.written.push_back(std::move(path));
    }
    // Frame 0 is not representative: it classifies every probe and builds shadow maps and
    // pipelines once; teaching the budget controller its cost would starve the next frames.
    if (o.update_probes && k > 0)
      scheduler_.observe({.frame_ms = timings.total_ms(),
                          .probe_ms = update.seconds * 1e3,
                          .paths = update.paths,
                          .rays = update.rays});
    std::vector<probes::StageMs> stages;
    for (const metrics::StageTime& s : timings.stages) stages.push_back({s.name, s.ms});
    report.counts.schedule =
        probes::make_frame_record(k, plan, update, std::move(stages), scheduler_.budget());
    result.timings.add(timings);
    result.counts.push_back(report.counts);
    report.timings = &result.timings.frames().back();
    if (progress) progress(report);
  }
  return result;
}

}  // namespace ddish::app
