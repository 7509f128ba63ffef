// Scheduling for several clients at once (the probe server's case, `ddish serve`): two clients look
// at opposite halves of a room, and the scheduler plans from the union of their views. With a
// budget per client (the server's tick budget = per-client budget x clients), each half's probe
// error falls at least as fast as for one client looking at that half alone; under one shared
// budget it falls more slowly (half the paths each). The budget is held in
// paths (a controller that never learns keeps its prior cost per path, as in test_scheduler.cpp),
// so the plans, and with seeded samplers the errors, are deterministic.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "probes/priority.h"
#include "probes/probe_tracer.h"
#include "probes/scheduler.h"
#include "synthetic_sources.h"

using namespace ddish::probes;
using ddish::probes::synthetic::FunctionSource;
using ddish::scene::Aabb;
using ddish::scene::View;
using ddish::trace::PathSample;
using ddish::trace::Ray;
using ddish::trace::Sampler;

namespace {

constexpr std::uint32_t kSamples = 8;
constexpr std::uint32_t kProbesPerClient = 16;  // paths of 16 probes a frame per client
constexpr int kFrames = 12;
// Seeds per case: one run's RMS over a half's 88 probes varies by ~7 % with the noise alone, so the
// errors are taken over 8 independent runs (~2.7 %, a ratio of two ~4 %).
constexpr std::uint64_t kSeeds = 8;

// 8 x 4 x 8 probes over a 16 x 8 x 16 m room centred on the origin.
ProbeVolume room() {
  return ProbeVolume(ProbeGrid(Aabb{{-8.0f, -4.0f, -8.0f}, {8.0f, 4.0f, 8.0f}}, {8, 4, 8}));
}

// Client A looks down -z from the room's centre, client B down +z: halves that barely overlap.
View client_view(float dz) {
  return ddish::scene::look_at_view({0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, dz}, {0.0f, 1.0f, 0.0f},
                                    std::numbers::pi_v<float> / 3.0f, 320, 240, 0.1f, 100.0f);
}

// Radiance 1 from everywhere plus uniform noise in [-1, 1]: a probe's L0 error shrinks as 1 /
// sqrt(its samples) while its running average still weighs every update equally.
PathSample noisy(const Ray&, Sampler& sampler) {
  PathSample s;
  s.radiance = glm::vec3(1.0f + (2.0f * sampler.next1d() - 1.0f));
  return s;
}

// The probes only `mine` sees (of the two views), for the error of that client's half.
std::vector<std::uint32_t> half(const ProbeVolume& volume, const View& mine, const View& other,
                                const PriorityOptions& o) {
  const ProbePriorities a = compute_priorities(volume, std::vector<View>{mine}, o);
  const ProbePriorities b = compute_priorities(volume, std::vector<View>{other}, o);
  std::vector<std::uint32_t> out;
  for (std::uint32_t i = 0; i < volume.probe_count(); ++i)
    if (a.in_view[i] && !b.in_view[i]) out.push_back(i);
  return out;
}

// RMS L0 error over each half's own probes and every seed.
struct Errors {
  double a = 0.0, b = 0.0;
};

// kFrames frames scheduled for `views` under a budget of `clients_budget` clients' paths, once per
// seed; the L0 (red) error of each half against the converged value, whose L0 coefficient is that
// of radiance 1: sqrt(4 pi).
Errors run(const std::vector<View>& views, double clients_budget) {
  double sum_a = 0.0, sum_b = 0.0;
  std::size_t n_a = 0, n_b = 0;
  for (std::uint64_t seed = 1; seed <= kSeeds; ++seed) {
    ProbeVolume volume = room();
    SchedulerOptions o;
    o.samples = kSamples;
    o.min_samples = kSamples;
    o.priority.max_age = 1000;  // no max-age pacing: the budget goes by the views alone
    o.budget.initial_ms_per_path = 1e-3;
    o.budget.budget_ms = (clients_budget * kProbesPerClient + 0.5) * kSamples * 1e-3;
    Scheduler scheduler(o);
    FunctionSource source(noisy);
    ProbeTracer tracer(source, UpdateOptions{.samples = kSamples, .seed = seed});
    for (int frame = 0; frame < kFrames; ++frame) {
      const FramePlan plan = scheduler.plan(volume, views);
      EXPECT_EQ(plan.probes.size(), std::size_t(clients_budget * kProbesPerClient));
      UpdateOptions u = tracer.options();
      u.samples = plan.samples;
      u.hysteresis = plan.hysteresis;
      tracer.set_options(u);
      tracer.update(volume, plan.probes);
    }
    const double truth = std::sqrt(4.0 * std::numbers::pi);
    const auto add = [&](const std::vector<std::uint32_t>& probes, double& sum, std::size_t& n) {
      for (std::uint32_t p : probes) {
        // A probe never updated holds 0: its error is the whole value, as a client would see it.
        const double e = double(volume.coefficients(p)[0].x) - truth;
        sum += e * e;
      }
      n += probes.size();
    };
    add(half(volume, client_view(-1.0f), client_view(1.0f), o.priority), sum_a, n_a);
    add(half(volume, client_view(1.0f), client_view(-1.0f), o.priority), sum_b, n_b);
  }
  return {std::sqrt(sum_a / double(n_a)), std::sqrt(sum_b / double(n_b))};
}

TEST(SchedulerClients, EachHalfConvergesAsForOneClientWithABudgetPerClient) {
  const View a = client_view(-1.0f), b = client_view(1.0f);
  {
    const ProbeVolume v = room();
    const std::size_t na = half(v, a, b, {}).size(), nb = half(v, b, a, {}).size();
    ASSERT_GE(na, 40u);  // enough that 16 a frame cannot cover a half in 2 frames
    ASSERT_EQ(na, nb);   // the room is symmetric
  }
  const Errors alone_a = run({a}, 1.0);
  const Errors alone_b = run({b}, 1.0);
  const Errors both = run({a, b}, 2.0);    // the server's budget: one client's per client
  const Errors shared = run({a, b}, 1.0);  // one client's budget split between two

  // Measured (8 seeds): the lone clients' halves 0.704 and 0.734; with a budget per client 0.620
  // and 0.633, a little better than alone, because the probes both clients see (near the room's
  // centre, in neither half) are paid for once for two; under the shared budget 1.044 and 1.477.
  // The bounds leave 3 sigmas of the ratios' noise (about 4 %).
  EXPECT_LT(both.a / alone_a.a, 1.05) << both.a << " vs " << alone_a.a;
  EXPECT_LT(both.b / alone_b.b, 1.05) << both.b << " vs " << alone_b.b;
  // ... and no better than the overlap explains: the same regime, not more paths.
  EXPECT_GT(both.a / alone_a.a, 0.75) << both.a << " vs " << alone_a.a;
  EXPECT_GT(both.b / alone_b.b, 0.75) << both.b << " vs " << alone_b.b;
  EXPECT_GT(shared.a / alone_a.a, 1.3) << shared.a << " vs " << alone_a.a;
  EXPECT_GT(shared.b / alone_b.b, 1.3) << shared.b << " vs " << alone_b.b;
  // A lone client's budget goes to its own half: the other half is left far behind.
  EXPECT_GT(alone_a.b, 2.0 * alone_a.a);
}

}  // namespace
