// The frame-budget controller against a synthetic cost model (no clocks): it must bring the
// frame time within 5% of the budget in a few frames, stay there under noise, and follow a step
// in the tracer's cost.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "probes/budget.h"

using namespace ddish::probes;

namespace {

// A deterministic uniform number in [-1, 1] (a 64-bit LCG; the test must not depend on a
// standard library's distributions).
class Noise {
 public:
  explicit Noise(std::uint64_t seed) : state_(seed) {}
  double next() {
    state_ = state_ * 6364136223846793005ull + 1442695040888963407ull;
    return double(state_ >> 11) / double(1ull << 53) * 2.0 - 1.0;
  }

 private:
  std::uint64_t state_;
};

// The frame the controller does not know: rest-of-frame work (raster, upload) plus a probe
// update with a fixed overhead and a cost per path, both noisy.
struct CostModel {
  double rest_ms = 6.0;
  double rest_noise_ms = 0.2;
  double probe_overhead_ms = 0.4;
  double ms_per_path = 2e-4;
  double path_noise = 0.03;  // relative
  double rays_per_path = 3.0;

  FrameCost frame(std::uint64_t paths, Noise& noise) const {
    FrameCost c;
    c.paths = paths;
    c.rays = std::uint64_t(double(paths) * rays_per_path);
    c.probe_ms = probe_overhead_ms + double(paths) * ms_per_path * (1.0 + path_noise * noise.next());
    c.frame_ms = rest_ms + rest_noise_ms * noise.next() + c.probe_ms;
    return c;
  }
};

// Runs frames [0, frames) and returns each frame's time; `step` changes the model at a frame.
std::vector<double> simulate(BudgetController& controller, CostModel model, int frames,
                             int step_frame = -1, double step_ms_per_path = 0.0) {
  Noise noise(42);
  std::vector<double> times;
  for (int f = 0; f < frames; ++f) {
    if (f == step_frame) model.ms_per_path = step_ms_per_path;
    FrameCost c = model.frame(controller.path_allowance(), noise);
    controller.observe(c);
    times.push_back(c.frame_ms);
  }
  return times;
}

// The first frame from which every later frame in [from, to) is within tol of budget.
int settled_from(const std::vector<double>& t, double budget, double tol, int from, int to) {
  int settled = to;
  for (int f = to - 1; f >= from; --f) {
    if (std::abs(t[std::size_t(f)] - budget) > tol * budget) break;
    settled = f;
  }
  return settled;
}

}  // namespace

TEST(BudgetController, ConvergesWithinFivePercentAndStays) {
  BudgetOptions o;
  o.budget_ms = 16.0;
  BudgetController c(o);
  // The prior (5e-4 ms per path) is 2.5x the true cost: the first frame undershoots.
  std::vector<double> t = simulate(c, CostModel{}, 100);
  EXPECT_LT(t[0], 0.8 * o.budget_ms);
  const int settled = settled_from(t, o.budget_ms, 0.05, 0, 100);
  EXPECT_LE(settled, 8);
  // The estimate has found the cost per path at the operating point: 2e-4 plus the overhead
  // spread over the ~48,000 paths of a 9.6 ms probe update.
  EXPECT_NEAR(c.ms_per_path(), 2e-4 + 0.4 / 48000.0, 0.1 * 2e-4);
  EXPECT_NEAR(c.rest_ms(), 6.0, 0.2);
  EXPECT_NEAR(c.mrays_per_second(), 3.0 / (2e-4 + 0.4 / 48000.0) * 1e-3, 0.5);
  double mean = 0.0;
  for (int f = 50; f < 100; ++f) mean += t[std::size_t(f)] / 50.0;
  EXPECT_NEAR(mean, o.budget_ms, 0.01 * o.budget_ms);  // no bias
}

TEST(BudgetController, FollowsAStepInTheTracerCost) {
  BudgetOptions o;
  o.budget_ms = 16.0;
  BudgetController c(o);
  // At frame 60 every path costs twice as much (a heavier scene part, a busier machine), at
  // frame 120 half as much as at first.
  Noise noise(7);
  CostModel model;
  std::vector<double> t;
  for (int f = 0; f < 180; ++f) {
    if (f == 60) model.ms_per_path = 4e-4;
    if (f == 120) model.ms_per_path = 1e-4;
    FrameCost fc = model.frame(c.path_allowance(), noise);
    c.observe(fc);
    t.push_back(fc.frame_ms);
  }
  EXPECT_LE(settled_from(t, 16.0, 0.05, 0, 60), 8);
  EXPECT_GT(t[60], 1.4 * 16.0);  // the step itself cannot be foreseen
  EXPECT_LE(settled_from(t, 16.0, 0.05, 60, 120), 60 + 10);
  EXPECT_LT(t[120], 0.8 * 16.0);
  EXPECT_LE(settled_from(t, 16.0, 0.05, 120, 180), 120 + 10);
  // No ringing: after each step the frames approach the budget from one side, with less than
  // 10% error in the other direction.
  for (int f = 61; f < 120; ++f) EXPECT_GT(t[std::size_t(f)], 0.9 * 16.0) << f;
  for (int f = 121; f < 180; ++f) EXPECT_LT(t[std::size_t(f)], 1.1 * 16.0) << f;
}

TEST(BudgetController, FollowsHeavierRasterWork) {
  BudgetOptions o;
  o.budget_ms = 33.0;
  BudgetController c(o);
  Noise noise(3);
  CostModel model;
  std::vector<double> t;
  for (int f = 0; f < 80; ++f) {
    if (f == 40) model.rest_ms = 20.0;  // twice the views
    FrameCost fc = model.frame(c.path_allowance(), noise);
    c.observe(fc);
    t.push_back(fc.frame_ms);
  }
  EXPECT_LE(settled_from(t, 33.0, 0.05, 40, 80), 40 + 6);
}

TEST(BudgetController, UnlimitedAndImpossibleBudgets) {
  BudgetController none(BudgetOptions{});
  EXPECT_FALSE(none.limited());
  EXPECT_EQ(none.path_allowance(), std::numeric_limits<std::uint64_t>::max());
  none.observe({.frame_ms = 50.0, .probe_ms = 20.0, .paths = 100000, .rays = 300000});
  EXPECT_DOUBLE_EQ(none.ms_per_path(), 2e-4);
  EXPECT_DOUBLE_EQ(none.last_error_ms(), 0.0);

  // The rest of the frame alone exceeds the budget: no paths (the scheduler still keeps its
  // mandatory probes).
  BudgetController tight(BudgetOptions{.budget_ms = 10.0});
  tight.observe({.frame_ms = 15.0, .probe_ms = 1.0, .paths = 1000, .rays = 1000});
  EXPECT_DOUBLE_EQ(tight.probe_ms_allowance(), 0.0);
  EXPECT_EQ(tight.path_allowance(), 0u);

  // Measurements that are not numbers are ignored.
  tight.observe({.frame_ms = std::nan(""), .probe_ms = 1.0, .paths = 10, .rays = 10});
  EXPECT_EQ(tight.frames_observed(), 1u);

  EXPECT_THROW(BudgetController(BudgetOptions{.budget_ms = std::nan("")}), std::invalid_argument);
  EXPECT_THROW(BudgetController(BudgetOptions{.cost_smoothing = 0.0}), std::invalid_argument);
  EXPECT_THROW(BudgetController(BudgetOptions{.gain = 1.0}), std::invalid_argument);
  EXPECT_THROW(BudgetController(BudgetOptions{.initial_ms_per_path = 0.0}),
               std::invalid_argument);
}
