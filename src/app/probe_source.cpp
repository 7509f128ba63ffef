#include "app/probe_source.h"

#include <algorithm>
#include <chrono>

#include "probes/probe_volume.h"
#include "scene/scene.h"

namespace ddish::app {

InProcessProbes::InProcessProbes(ProbeEngine& engine, probes::Scheduler& scheduler,
                                 UpdateOptionsFor update_options, probes::ProbeVolume& volume)
    : engine_(engine),
      probe_tracer_(engine.updater()),
      scheduler_(scheduler),
      update_options_(std::move(update_options)),
      volume_(volume) {
  last_flags_.resize(volume.probe_count());
  for (std::uint32_t i = 0; i < volume.probe_count(); ++i) last_flags_[i] = volume.state(i).flags;
}

std::vector<std::uint32_t> InProcessProbes::changed_probes(const std::vector<std::uint32_t>& traced) {
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

void InProcessProbes::posed(const scene::Scene& scene, const std::vector<int>& moved,
                            metrics::FrameTimings& timings) {
  if (scene.animations.empty()) return;
  metrics::StageTimer timer(timings, "tracer_update");  // lights may move without any instance moving
  engine_.posed(scene, moved);
}

ProbeStep InProcessProbes::update(const std::vector<scene::View>& views, bool enabled,
                                  metrics::FrameTimings& timings, FrameCounts& counts) {
  ProbeStep step;
  const std::uint64_t updates_before = volume_.frame();
  if (enabled) {
    metrics::StageTimer timer(timings, "probe_update");
    step.plan = scheduler_.plan(volume_, views);
    probe_tracer_.set_options(update_options_(step.plan));
    step.update = probe_tracer_.update(volume_, step.plan.probes);  // the frame's one probe update
    counts.probes_traced = step.update.probes_traced;
  }
  counts.probe_updates = volume_.frame() - updates_before;
  counts.probe_rays = step.update.rays;
  step.changed = changed_probes(step.plan.probes);
  return step;
}

void InProcessProbes::finished(int frame, const metrics::FrameTimings& timings,
                               const ProbeStep& step, bool enabled, FrameCounts& counts) {
  // Frame 0 is not representative: it classifies every probe and builds shadow maps and
  // pipelines once; teaching the budget controller its cost would starve the next frames.
  if (enabled && frame > 0)
    scheduler_.observe({.frame_ms = timings.total_ms(),
                        .probe_ms = step.update.seconds * 1e3,
                        .paths = step.update.paths,
                        .rays = step.update.rays});
  std::vector<probes::StageMs> stages;
  for (const metrics::StageTime& s : timings.stages) stages.push_back({s.name, s.ms});
  counts.schedule =
      probes::make_frame_record(frame, step.plan, step.update, std::move(stages), scheduler_.budget());
}

WarmupReport InProcessProbes::warm_up(const WarmupOptions& options) {
  WarmupReport report;
  if (!options.enabled()) return report;
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  const auto ms_since = [](clock::time_point t) {
    return std::chrono::duration<double, std::milli>(clock::now() - t).count();
  };
  // The plan of a frame with no budget: every active probe at S samples with alpha.
  probes::FramePlan plan;
  plan.samples = scheduler_.options().samples;
  plan.hysteresis = scheduler_.options().hysteresis;
  plan.mode = scheduler_.options().mode;
  probe_tracer_.set_options(update_options_(plan));
  std::vector<std::uint32_t> traced;
  double last_round_ms = 0.0;
  while (report.samples_per_probe < options.samples) {
    if (report.rounds > 0 && ms_since(start) + last_round_ms > options.max_ms) {
      report.bounded = true;
      break;
    }
    std::vector<std::uint32_t> active;
    for (std::uint32_t i = 0; i < volume_.probe_count(); ++i)
      if (volume_.state(i).active()) active.push_back(i);
    if (active.empty()) break;
    const auto round = clock::now();
    probe_tracer_.update(volume_, active);
    last_round_ms = ms_since(round);
    ++report.rounds;
    report.samples_per_probe += plan.samples;
    std::vector<std::uint32_t> merged;
    std::set_union(traced.begin(), traced.end(), active.begin(), active.end(), std::back_inserter(merged));
    traced = std::move(merged);
  }
  report.changed = changed_probes(traced);
  for (std::uint32_t i = 0; i < volume_.probe_count(); ++i)
    if (volume_.state(i).active()) ++report.probes;
  report.ms = ms_since(start);
  return report;
}

}  // namespace ddish::app
