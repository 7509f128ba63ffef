#include "probes/budget.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace ddish::probes {

void check_budget_options(const BudgetOptions& o) {
  if (!std::isfinite(o.budget_ms))
    throw std::invalid_argument("frame budget must be a finite number of milliseconds");
  auto weight = [](double w, const char* what) {
    if (!(w > 0.0 && w <= 1.0))
      throw std::invalid_argument(std::string(what) + " must be in (0, 1], got " +
                                  std::to_string(w));
  };
  weight(o.cost_smoothing, "cost smoothing");
  weight(o.rest_smoothing, "rest-of-frame smoothing");
  if (!(o.gain >= 0.0 && o.gain < 1.0))
    throw std::invalid_argument("budget gain must be in [0, 1), got " + std::to_string(o.gain));
  if (!(o.initial_ms_per_path > 0.0) || !std::isfinite(o.initial_ms_per_path))
    throw std::invalid_argument("initial ms per path must be > 0");
  if (!(o.headroom_sigmas >= 0.0) || !std::isfinite(o.headroom_sigmas))
    throw std::invalid_argument("budget headroom must be a finite number of sigmas >= 0");
  if (o.jitter_window == 0) throw std::invalid_argument("the jitter window must hold a frame");
}

BudgetController::BudgetController(const BudgetOptions& options)
    : options_(options), ms_per_path_(options.initial_ms_per_path) {
  check_budget_options(options);
}

double BudgetController::probe_ms_allowance() const {
  if (!limited()) return std::numeric_limits<double>::infinity();
  return std::max(0.0, target_ms() - rest_ms_ - options_.gain * over_target_ms_);
}

std::uint64_t BudgetController::path_allowance() const {
  if (!limited()) return std::numeric_limits<std::uint64_t>::max();
  const double paths = std::floor(probe_ms_allowance() / ms_per_path_);
  // A cost per path of ~0 (a frame that measured nothing) must not overflow the conversion.
  if (!(paths < 9.0e18)) return std::numeric_limits<std::uint64_t>::max();
  return std::uint64_t(paths);
}

void BudgetController::observe(const FrameCost& c) {
  if (!std::isfinite(c.frame_ms) || !std::isfinite(c.probe_ms) || c.frame_ms < 0.0 ||
      c.probe_ms < 0.0)
    return;
  // What the model predicted for this frame, before it learns from it: its miss is the jitter
  // that the headroom must absorb.
  if (frames_ > 0) {
    const double predicted = rest_ms_ + double(c.paths) * ms_per_path_;
    const double miss = std::abs(c.frame_ms - predicted);
    if (misses_.size() < options_.jitter_window) misses_.push_back(miss);
    else misses_[std::size_t((frames_ - 1) % options_.jitter_window)] = miss;
  }
  const double rest = std::max(0.0, c.frame_ms - c.probe_ms);
  // The first frame replaces the zero start instead of averaging with it.
  rest_ms_ = frames_ == 0 ? rest : rest_ms_ + options_.rest_smoothing * (rest - rest_ms_);
  if (c.paths > 0 && c.probe_ms > 0.0) {
    const double measured = c.probe_ms / double(c.paths);
    ms_per_path_ = traced_ ? ms_per_path_ + options_.cost_smoothing * (measured - ms_per_path_)
                           : measured;
    const double mrays = double(c.rays) / c.probe_ms * 1e-3;
    mrays_per_second_ = traced_ ? mrays_per_second_ +
                                      options_.cost_smoothing * (mrays - mrays_per_second_)
                                : mrays;
    traced_ = true;
  }
  if (limited() && !misses_.empty()) {
    std::vector<double> sorted = misses_;
    std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(sorted.size() / 2), sorted.end());
    const double sigma = 1.4826 * sorted[sorted.size() / 2];
    headroom_ms_ = std::min(0.5 * options_.budget_ms, options_.headroom_sigmas * sigma);
  }
  error_ms_ = limited() ? c.frame_ms - options_.budget_ms : 0.0;
  over_target_ms_ = limited() ? c.frame_ms - target_ms() : 0.0;
  ++frames_;
}

void BudgetController::set_budget_ms(double budget_ms) {
  if (!std::isfinite(budget_ms)) throw std::invalid_argument("the frame budget must be finite");
  options_.budget_ms = budget_ms;
  if (!limited()) headroom_ms_ = 0.0;
  headroom_ms_ = std::min(headroom_ms_, 0.5 * std::max(0.0, budget_ms));
}

}  // namespace ddish::probes
