// The frame-time budget controller: how many probe paths this frame may trace so that the
// whole frame (views' rasterization, upload, output and the probe update) fits a budget.
//
// Model: frame_ms = rest_ms + paths * ms_per_path. Both terms are learnt from the frames before:
//   rest_ms      exponential average of (frame_ms - probe_ms), weight rest_smoothing;
//   ms_per_path  exponential average of probe_ms / paths (frames that traced), weight
//                cost_smoothing. Fixed costs of the probe stage (threads starting, the per-frame
//                aging pass) fold into it at the operating point, where they are what counts.
// Headroom: a controller that aims at the budget itself overruns it in half of the frames,
// because frame times jitter around any prediction (on the 2-core machine about 7 % of a 40 ms
// frame). It therefore aims at target_ms = budget_ms - headroom_ms, where
//   headroom_ms = headroom_sigmas * sigma,  sigma = 1.4826 * median |frame_ms - predicted_ms|
// over the last jitter_window frames (the median absolute deviation: a step in the cost, which
// spoils a few predictions, does not inflate it the way a variance would), at most half the
// budget. With 1.3 sigmas about 90 % of frames land within the budget for normal jitter.
// Allowance for the next frame, with a proportional correction of the last frame's error
// e = frame_ms - target_ms (the part of a change the averages have not caught up with yet):
//   probe_ms = max(0, target_ms - rest_ms - gain * e),   paths = probe_ms / ms_per_path.
// In steady state e averages to zero, so the correction only speeds up the reaction to a step
// (a heavier view, a slower tracer) and costs no bias. The defaults settle a doubling or a
// quartering of the cost per path within 5% of the budget in about 5 frames without
// overshooting by more than 10% (tests/probes/test_budget_controller.cpp); a smaller
// cost_smoothing filters noisier measurements but follows steps more slowly.
// No budget (budget_ms <= 0): unlimited; the controller still tracks the rates for the log.
#pragma once

#include <cstdint>
#include <vector>

namespace ddish::probes {

struct BudgetOptions {
  double budget_ms = 0.0;          // the whole frame (--budget-ms, or per view x N); <= 0: none
  double cost_smoothing = 0.5;     // weight of the newest ms-per-path measurement
  double rest_smoothing = 0.5;     // weight of the newest rest-of-frame measurement
  double gain = 0.2;               // allowance ms removed per ms the last frame ran over
  double headroom_sigmas = 1.3;    // target this many jitter sigmas below the budget; 0: none
  std::uint32_t jitter_window = 16;  // frames whose prediction errors estimate the jitter
  // ms per path before anything was measured: DESIGN.md's 1024 probes x 256 paths in ~60 ms on
  // two cores is 2.3e-4; twice that, so a first frame rather undershoots than overruns.
  double initial_ms_per_path = 5e-4;
};

// Throws std::invalid_argument for a non-finite budget, smoothing weights outside (0, 1],
// a gain outside [0, 1), initial_ms_per_path <= 0, negative or non-finite headroom_sigmas or
// a jitter_window of 0.
void check_budget_options(const BudgetOptions& options);

// What a frame cost, measured after it.
struct FrameCost {
  double frame_ms = 0.0;     // wall time of the whole frame, probe update included
  double probe_ms = 0.0;     // the probe update (UpdateStats::seconds * 1000)
  std::uint64_t paths = 0;   // UpdateStats::paths
  std::uint64_t rays = 0;    // UpdateStats::rays
};

class BudgetController {
 public:
  explicit BudgetController(const BudgetOptions& options);

  const BudgetOptions& options() const { return options_; }
  bool limited() const { return options_.budget_ms > 0.0; }

  // Milliseconds and paths the next frame's probe update may take (unlimited: infinity and
  // UINT64_MAX).
  double probe_ms_allowance() const;
  std::uint64_t path_allowance() const;

  // Changes the budget from the next plan on (a display whose period changes: OpenXR's
  // predictedDisplayPeriod); what was learnt (rates, rest of the frame, jitter) is kept, so the
  // allowance follows the new budget at once. <= 0: none. Throws std::invalid_argument when
  // non-finite.
  void set_budget_ms(double budget_ms);
  // Learns from a finished frame (negative or non-finite measurements are ignored).
  void observe(const FrameCost& cost);

  double ms_per_path() const { return ms_per_path_; }
  double rest_ms() const { return rest_ms_; }
  // Smoothed tracer rate from the measured rays and time, 0 before the first traced frame.
  double mrays_per_second() const { return mrays_per_second_; }
  double last_error_ms() const { return error_ms_; }  // last frame_ms - budget_ms (0: none)
  // The jitter margin kept below the budget and the frame time aimed at (budget - headroom).
  double headroom_ms() const { return headroom_ms_; }
  double target_ms() const { return options_.budget_ms - headroom_ms_; }
  std::uint64_t frames_observed() const { return frames_; }

 private:
  BudgetOptions options_;
  double ms_per_path_;
  double rest_ms_ = 0.0;
  double mrays_per_second_ = 0.0;
  double error_ms_ = 0.0;
  double over_target_ms_ = 0.0;         // last frame_ms - target_ms
  double headroom_ms_ = 0.0;
  std::vector<double> misses_;          // |frame_ms - predicted_ms|, a ring of jitter_window
  std::uint64_t frames_ = 0;
  bool traced_ = false;  // a frame with paths has been seen: ms_per_path is measured
};

}  // namespace ddish::probes
