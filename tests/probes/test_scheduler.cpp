// The scheduler's plans: uniform mode, no budget, the max-age promise under a tight budget with
// the real probe tracer (inactive probes receive no rays), reduced samples, and the frame log.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "probes/probe_tracer.h"
#include "probes/scheduler.h"
#include "probes/scheduler_record.h"
#include "synthetic_sources.h"

using namespace ddish::probes;
using ddish::probes::synthetic::FunctionSource;
namespace synthetic = ddish::probes::synthetic;
using ddish::scene::Aabb;
using ddish::scene::View;
using ddish::trace::PathSample;
using ddish::trace::Ray;
using ddish::trace::Sampler;

namespace {

// 8 x 4 x 8 probes over a 16 x 8 x 16 m room centred on the origin (2 m spacing).
ProbeVolume room() {
  return ProbeVolume(ProbeGrid(Aabb{{-8.0f, -4.0f, -8.0f}, {8.0f, 4.0f, 8.0f}}, {8, 4, 8}));
}

// From the room's centre looking down -z: about half the probes are in view.
View view_down_minus_z() {
  return ddish::scene::look_at_view({0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f}, {0.0f, 1.0f, 0.0f},
                                    std::numbers::pi_v<float> / 3.0f, 320, 240, 0.1f, 100.0f);
}

// A source that counts the rays each probe casts (found from the ray origin).
class CountingSource {
 public:
  explicit CountingSource(const ProbeGrid& grid)
      : grid_(grid), counts_(new std::atomic<std::uint64_t>[grid.probe_count()]) {
    for (std::uint32_t i = 0; i < grid.probe_count(); ++i) counts_[i] = 0;
    source_ = std::make_unique<FunctionSource>([this](const Ray& r, Sampler&) {
      const glm::vec3 g = grid_.grid_coordinate(r.origin);
      const glm::ivec3 cell(std::lround(g.x), std::lround(g.y), std::lround(g.z));
      counts_[grid_.index(cell)].fetch_add(1, std::memory_order_relaxed);
      return synthetic::uniform(glm::vec3(1.0f));
    });
  }
  const RadianceSource& source() const { return *source_; }
  std::uint64_t rays(std::uint32_t probe) const { return counts_[probe].load(); }

 private:
  ProbeGrid grid_;
  std::unique_ptr<std::atomic<std::uint64_t>[]> counts_;
  std::unique_ptr<FunctionSource> source_;
};

}  // namespace

TEST(ScheduleMode, ParsesNamesAndRejectsOthers) {
  EXPECT_EQ(parse_schedule_mode("uniform"), ScheduleMode::uniform);
  EXPECT_EQ(parse_schedule_mode("visibility"), ScheduleMode::visibility);
  EXPECT_STREQ(schedule_mode_name(ScheduleMode::uniform), "uniform");
  EXPECT_STREQ(schedule_mode_name(ScheduleMode::visibility), "visibility");
  try {
    parse_schedule_mode("frustum");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "unknown schedule 'frustum' (uniform or visibility)");
  }
  EXPECT_EQ(SchedulerOptions{}.mode, ScheduleMode::visibility);  // the default
}

TEST(Scheduler, UniformModeTakesEveryActiveProbeWithFullSamples) {
  ProbeVolume volume = room();
  volume.deactivate(3, true);
  volume.deactivate(100, false);
  SchedulerOptions o;
  o.mode = ScheduleMode::uniform;
  o.samples = 64;
  o.hysteresis = 0.9f;
  o.budget.budget_ms = 1.0;  // ignored: uniform is the published behaviour
  Scheduler s(o);
  std::vector<View> views{view_down_minus_z()};
  FramePlan plan = s.plan(volume, views);
  ASSERT_EQ(plan.probes.size(), 254u);
  EXPECT_EQ(plan.samples, 64u);
  EXPECT_FLOAT_EQ(plan.hysteresis, 0.9f);
  EXPECT_EQ(plan.paths, 254u * 64u);
  EXPECT_EQ(plan.skipped, 0u);
  for (std::uint32_t p : plan.probes) EXPECT_TRUE(p != 3 && p != 100);

  // Visibility mode without a budget does the same.
  o.mode = ScheduleMode::visibility;
  o.budget.budget_ms = 0.0;
  FramePlan unlimited = Scheduler(o).plan(volume, views);
  EXPECT_EQ(unlimited.probes, plan.probes);
  EXPECT_EQ(unlimited.samples, 64u);
  EXPECT_GT(unlimited.in_view, 0u);
  EXPECT_EQ(unlimited.in_view_traced, unlimited.in_view);
}

namespace {

// 100 frames of plan + update at 20 probes' worth of paths per frame; checks the max-age
// promise, the rays per probe, and the plan sizes.
void run_max_age_frames(ProbeVolume& volume) {
  const std::vector<std::uint32_t> dead{0, 17, 77, 130, 255};
  for (std::uint32_t p : dead) volume.deactivate(p, true);
  CountingSource counter(volume.grid());

  SchedulerOptions o;
  o.samples = 8;
  o.min_samples = 4;
  o.priority.max_age = 30;
  // 20 probes' worth of paths per frame (the controller never learns: its prior holds), of
  // 251 active ones; pacing needs ceil(251 / 30) = 9 per frame.
  o.budget.budget_ms = 20.5 * o.samples * 1e-3;
  o.budget.initial_ms_per_path = 1e-3;
  Scheduler scheduler(o);
  std::vector<View> views{view_down_minus_z()};
  ProbeTracer tracer(counter.source(), UpdateOptions{.samples = o.samples, .seed = 3});

  std::vector<std::uint32_t> updates(volume.probe_count(), 0);
  std::uint32_t max_age_seen = 0;
  for (int frame = 0; frame < 100; ++frame) {
    FramePlan plan = scheduler.plan(volume, views);
    EXPECT_EQ(plan.probes.size(), 20u);
    EXPECT_EQ(plan.samples, o.samples);
    for (std::uint32_t p : plan.probes) {
      EXPECT_TRUE(volume.state(p).active()) << p;
      ++updates[p];
    }
    UpdateOptions u = tracer.options();
    u.samples = plan.samples;
    u.hysteresis = plan.hysteresis;
    tracer.set_options(u);
    UpdateStats stats = tracer.update(volume, plan.probes);
    EXPECT_EQ(stats.probes_traced, 20u);
    for (std::uint32_t i = 0; i < volume.probe_count(); ++i)
      if (volume.state(i).active()) max_age_seen = std::max(max_age_seen, volume.state(i).age);
  }
  // The promise holds with no slack: oldest-first pacing refreshes every probe in time.
  EXPECT_LE(max_age_seen, 30u);
  for (std::uint32_t p : dead) {
    EXPECT_EQ(counter.rays(p), 0u) << p;
    EXPECT_EQ(updates[p], 0u);
  }
  // Probes in view are updated more often than those behind the camera (which get the pacing
  // rate, about 100 / 30 times in 100 frames).
  ProbePriorities pr = compute_priorities(volume, views, o.priority);
  double in = 0, out = 0;
  std::uint32_t n_in = 0, n_out = 0;
  for (std::uint32_t i = 0; i < volume.probe_count(); ++i) {
    if (!pr.candidate[i]) continue;
    EXPECT_GE(updates[i], 3u) << i;  // at least every 30 frames over 100 frames
    EXPECT_EQ(counter.rays(i), std::uint64_t(updates[i]) * o.samples) << i;
    (pr.in_view[i] ? in : out) += updates[i];
    ++(pr.in_view[i] ? n_in : n_out);
  }
  ASSERT_GT(n_in, 0u);
  ASSERT_GT(n_out, 0u);
  EXPECT_GT(in / n_in, 1.5 * (out / n_out));
}

}  // namespace

TEST(Scheduler, MaxAgeHeldUnderTightBudgetAndInactiveProbesGetNoRays) {
  // From fresh probes (every probe's first update still to come).
  ProbeVolume fresh = room();
  run_max_age_frames(fresh);
  // From a volume whose probes were all updated in the same frame (after a uniform update, or
  // a bake): without pacing the unseen ones would all fall due together 30 frames later.
  ProbeVolume baked = room();
  for (std::uint32_t i = 0; i < baked.probe_count(); ++i) {
    ProbeState& st = baked.state(i);
    st.flags = 0;
    st.updates = 1;
    st.samples = 8;
    st.age = 0;
  }
  run_max_age_frames(baked);
}

TEST(Scheduler, ShortBudgetKeepsMandatoryProbesAtFewerSamples) {
  ProbeVolume volume = room();
  for (std::uint32_t i = 0; i < volume.probe_count(); ++i) {
    volume.state(i).flags = 0;
    volume.state(i).updates = 4;
    volume.state(i).samples = 1024;
    volume.state(i).age = 2;
  }
  volume.state(40).age = 30;  // overdue
  SchedulerOptions o;
  o.samples = 256;
  o.min_samples = 16;
  o.hysteresis = 0.95f;
  o.priority.max_age = 30;
  o.budget.initial_ms_per_path = 1e-3;
  // Mandatory: 1 overdue + 8 paced (ceil(256 / 30) = 9). 9 * 100 paths allowed: 100 each.
  o.budget.budget_ms = 0.9005;
  std::vector<View> views{view_down_minus_z()};
  FramePlan plan = Scheduler(o).plan(volume, views);
  ASSERT_EQ(plan.probes.size(), 9u);
  EXPECT_EQ(plan.overdue, 1u);
  EXPECT_EQ(plan.paced, 8u);
  EXPECT_EQ(plan.samples, 100u);
  EXPECT_FALSE(plan.over_allowance);
  EXPECT_NE(std::find(plan.probes.begin(), plan.probes.end(), 40u), plan.probes.end());
  // A tenth of the hysteresis-equivalent history N = 256 * 19 = 4864 samples: 1 - a' = 100 / 4964.
  EXPECT_NEAR(1.0 - plan.hysteresis, 100.0 / 4964.0, 1e-6);
  EXPECT_EQ(plan.skipped, 256u - 9u);
  // With the per-sample rule the volume weighs the samples itself: the plan keeps alpha.
  SchedulerOptions per_sample = o;
  per_sample.blend = BlendRule::per_sample;
  EXPECT_EQ(Scheduler(per_sample).plan(volume, views).hysteresis, 0.95f);

  // Less than min_samples each: still every mandatory probe, at min_samples, flagged.
  o.budget.budget_ms = 0.05;
  plan = Scheduler(o).plan(volume, views);
  EXPECT_EQ(plan.probes.size(), 9u);
  EXPECT_EQ(plan.samples, 16u);
  EXPECT_TRUE(plan.over_allowance);
}

TEST(Scheduler, FrameRecordJson) {
  ProbeVolume volume = room();
  SchedulerOptions o;
  o.samples = 16;
  o.budget.budget_ms = 10.0;
  o.budget.initial_ms_per_path = 1e-3;
  Scheduler scheduler(o);
  std::vector<View> views{view_down_minus_z()};
  FramePlan plan = scheduler.plan(volume, views);
  UpdateStats stats;
  stats.probes_traced = std::uint32_t(plan.probes.size());
  stats.paths = plan.paths;
  stats.rays = plan.paths * 3;
  stats.seconds = 0.004;
  scheduler.observe({.frame_ms = 9.0, .probe_ms = 4.0, .paths = plan.paths, .rays = stats.rays});
  SchedulerFrameRecord r = make_frame_record(7, plan, stats,
                                             {{"probe_update", 4.0}, {"raster", 5.0}},
                                             scheduler.budget());
  nlohmann::json j = r.to_json();
  EXPECT_EQ(j["frame"], 7);
  EXPECT_EQ(j["mode"], "visibility");
  EXPECT_DOUBLE_EQ(j["budget_ms"].get<double>(), 10.0);
  EXPECT_DOUBLE_EQ(j["frame_ms"].get<double>(), 9.0);
  EXPECT_EQ(j["within_budget"], true);
  EXPECT_DOUBLE_EQ(j["headroom_ms"].get<double>(), 0.0);  // no jitter measured before frame 1
  EXPECT_DOUBLE_EQ(j["stages_ms"]["raster"].get<double>(), 5.0);
  EXPECT_EQ(j["probes"]["traced"], plan.probes.size());
  EXPECT_EQ(j["probes"]["skipped"], 256u - plan.probes.size());
  EXPECT_EQ(j["probes"]["samples_per_probe"], 16);
  EXPECT_EQ(j["paths"], plan.paths);
  EXPECT_EQ(j["rays"], plan.paths * 3);
  EXPECT_DOUBLE_EQ(j["ms_per_path"].get<double>(), 4.0 / double(plan.paths));
  EXPECT_NEAR(j["mrays_per_second"].get<double>(), double(plan.paths * 3) / 4.0e-3 * 1e-6, 1e-9);
  // 10 ms at 1e-3 ms per path: 10000 paths, 625 probes of 16 samples > 256: all of them.
  EXPECT_EQ(plan.probes.size(), 256u);

  // No budget: nulls, not zeros or infinities.
  SchedulerOptions free = o;
  free.budget.budget_ms = 0.0;
  Scheduler unlimited(free);
  SchedulerFrameRecord u = make_frame_record(0, unlimited.plan(volume, views), stats, {},
                                             unlimited.budget());
  nlohmann::json ju = u.to_json();
  EXPECT_TRUE(ju["budget_ms"].is_null());
  EXPECT_TRUE(ju["within_budget"].is_null());
  EXPECT_TRUE(ju["probe_ms_allowance"].is_null());
  EXPECT_TRUE(ju["headroom_ms"].is_null());
  EXPECT_NO_THROW((void)ju.dump());
}

TEST(Scheduler, BadOptionsThrow) {
  EXPECT_THROW(Scheduler(SchedulerOptions{.samples = 0}), std::invalid_argument);
  EXPECT_THROW(Scheduler(SchedulerOptions{.samples = 16, .min_samples = 0}),
               std::invalid_argument);
  EXPECT_THROW(Scheduler(SchedulerOptions{.hysteresis = 1.0f}), std::invalid_argument);
  SchedulerOptions o;
  o.budget.gain = 1.5;
  EXPECT_THROW((Scheduler(o)), std::invalid_argument);
}
