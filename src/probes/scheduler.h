// The probe scheduler: once per frame, which probes the probe tracer updates and with how many
// samples, from all views at once (priority.h) and the frame budget (budget.h).
//
// Each frame (visibility mode, with a budget):
//   1. Mandatory probes, whatever the budget: every overdue probe (age >= max_age) and, oldest
//      first, enough others that ceil(active / max_age) probes are refreshed per frame, the
//      rate at which a round of all active probes takes max_age frames. This pacing keeps the
//      max-age promise without bursts of probes all falling due in one frame; the promise beats
//      the budget when the two collide (the frame log shows it as a plan over its allowance).
//   2. The path allowance A from the controller. With S the configured samples per probe:
//      if A allows floor(A / S) >= |mandatory| probes, that many probes are traced at S samples:
//      the mandatory ones, then the rest by priority. Otherwise only the mandatory probes are
//      traced, at n = clamp(floor(A / |mandatory|), min_samples, S) samples each.
//   One sample count per frame because one ProbeTracer::update traces all its probes alike
//   (and a volume update must be a single call: it ages every probe). A frame traced at n < S
//   samples blends with the hysteresis sample_equivalent_hysteresis(alpha, S, n), so its cheap
//   estimate weighs as little as its samples justify (accumulation.h; with the per-sample blend
//   rule the volume does this itself, per probe and with age decay, and the plan keeps alpha).
// Without a budget, or in uniform mode: every active probe at S samples with alpha.
// Inactive probes are never listed.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "probes/accumulation.h"
#include "probes/budget.h"
#include "probes/priority.h"
#include "probes/probe_volume.h"
#include "probes/scheduler_mode.h"
#include "scene/view.h"

namespace ddish::probes {

struct SchedulerOptions {
  ScheduleMode mode = ScheduleMode::visibility;
  std::uint32_t samples = 256;      // S: full samples per probe (--probe-samples)
  std::uint32_t min_samples = 32;   // fewest per probe when even the mandatory ones do not fit
                                    // (capped at samples)
  float hysteresis = kDefaultHysteresis;  // alpha (--hysteresis)
  // The blend rule the probe volume accumulates with. per_update: a frame at n < S samples gets
  // the sample-equivalent hysteresis in its plan; per_sample: the rule weighs samples itself,
  // so the plan keeps alpha.
  BlendRule blend = BlendRule::per_update;
  PriorityOptions priority;
  BudgetOptions budget;             // budget.budget_ms <= 0: no budget
};

// Throws std::invalid_argument for samples == 0, min_samples == 0, a bad
// hysteresis, or bad priority / budget options.
void check_scheduler_options(const SchedulerOptions& options);

// This frame's work and why.
struct FramePlan {
  std::vector<std::uint32_t> probes;  // increasing indices, active probes only
  std::uint32_t samples = 0;          // UpdateOptions::samples for this frame's update
  float hysteresis = kDefaultHysteresis;  // UpdateOptions::hysteresis for it

  ScheduleMode mode = ScheduleMode::visibility;
  double budget_ms = 0.0;             // 0: none
  double probe_ms_allowance = 0.0;    // what the controller allowed the probe update (inf: none)
  double headroom_ms = 0.0;           // the controller's jitter margin below the budget
  double predicted_probe_ms = 0.0;    // paths * the controller's ms per path
  std::uint64_t paths = 0;            // probes.size() * samples
  std::uint32_t active = 0;           // active probes in the volume
  std::uint32_t in_view = 0;          // active probes meeting a (widened) view frustum
  std::uint32_t in_view_traced = 0;   // of those, in this plan
  std::uint32_t overdue = 0;          // active probes at max_age (all in the plan)
  std::uint32_t paced = 0;            // taken oldest-first to keep the max-age rate
  std::uint32_t skipped = 0;          // active probes not in the plan
  bool over_allowance = false;        // the mandatory probes alone exceeded the allowance
};

class Scheduler {
 public:
  explicit Scheduler(const SchedulerOptions& options);

  const SchedulerOptions& options() const { return options_; }
  // Switches the mode from the next plan on (the live window's U key); the blend rule and the
  // budget controller's learnt costs stay.
  void set_mode(ScheduleMode mode) { options_.mode = mode; }
  const BudgetController& budget() const { return budget_; }

  // Plans the next update of `volume` for the views of this frame (any number, even none: then
  // nothing is in view and only the max-age refresh runs, within the budget).
  FramePlan plan(const ProbeVolume& volume, std::span<const scene::View> views) const;

  // The frame budget from the next plan on (budget.h: set_budget_ms); <= 0: none.
  void set_budget_ms(double budget_ms) {
    budget_.set_budget_ms(budget_ms);
    options_.budget.budget_ms = budget_ms;
  }
  // Tells the budget controller what the frame cost (after the frame).
  void observe(const FrameCost& cost) { budget_.observe(cost); }

 private:
  FramePlan plan_all(const ProbeVolume& volume, FramePlan plan) const;

  SchedulerOptions options_;
  BudgetController budget_;
};

}  // namespace ddish::probes
