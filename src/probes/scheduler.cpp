#include "probes/scheduler.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace ddish::probes {

void check_scheduler_options(const SchedulerOptions& o) {
  if (o.samples == 0) throw std::invalid_argument("probe samples must be at least 1");
  if (o.min_samples == 0) throw std::invalid_argument("minimum probe samples must be at least 1");
  check_hysteresis(o.hysteresis);
  check_priority_options(o.priority);
  check_budget_options(o.budget);
}

Scheduler::Scheduler(const SchedulerOptions& options)
    : options_(options), budget_(options.budget) {
  check_scheduler_options(options);
}

FramePlan Scheduler::plan_all(const ProbeVolume& volume, FramePlan plan) const {
  plan.probes.clear();
  for (std::uint32_t i = 0; i < volume.probe_count(); ++i)
    if (volume.state(i).active()) plan.probes.push_back(i);
  plan.samples = options_.samples;
  plan.hysteresis = options_.hysteresis;
  plan.paths = std::uint64_t(plan.probes.size()) * plan.samples;
  plan.predicted_probe_ms = double(plan.paths) * budget_.ms_per_path();
  plan.active = std::uint32_t(plan.probes.size());
  plan.skipped = 0;
  return plan;
}

FramePlan Scheduler::plan(const ProbeVolume& volume, std::span<const scene::View> views) const {
  FramePlan plan;
  plan.mode = options_.mode;
  plan.budget_ms = budget_.limited() ? options_.budget.budget_ms : 0.0;
  plan.probe_ms_allowance = budget_.probe_ms_allowance();
  plan.headroom_ms = budget_.headroom_ms();
  if (options_.mode == ScheduleMode::uniform) return plan_all(volume, std::move(plan));

  const ProbePriorities pr = compute_priorities(volume, views, options_.priority);
  plan.in_view = pr.in_view_count;
  plan.overdue = pr.overdue;
  if (!budget_.limited()) {
    plan = plan_all(volume, std::move(plan));
    plan.in_view_traced = pr.in_view_count;
    return plan;
  }

  const std::uint32_t n = volume.probe_count();
  const std::uint32_t max_age = options_.priority.max_age;
  // Candidates split into the overdue ones (all taken) and the rest.
  std::vector<std::uint32_t> mandatory, rest;
  mandatory.reserve(pr.overdue);
  rest.reserve(pr.active);
  for (std::uint32_t i = 0; i < n; ++i) {
    if (!pr.candidate[i]) continue;
    (pr.priority[i].tier == 2 ? mandatory : rest).push_back(i);
  }

  // Pacing: at least ceil(active / max_age) probes per frame, oldest first (ties by index, so
  // plans are deterministic). A probe waiting k frames has seen k * pace older-or-equal probes
  // updated before it; with pace * max_age >= active, k < max_age.
  const std::uint32_t pace = (pr.active + max_age - 1) / max_age;
  if (mandatory.size() < pace && !rest.empty()) {
    const std::size_t take = std::min<std::size_t>(pace - mandatory.size(), rest.size());
    auto older = [&](std::uint32_t a, std::uint32_t b) {
      const std::uint32_t aa = volume.state(a).age, ab = volume.state(b).age;
      return aa != ab ? aa > ab : a < b;
    };
    std::nth_element(rest.begin(), rest.begin() + std::ptrdiff_t(take - 1), rest.end(), older);
    mandatory.insert(mandatory.end(), rest.begin(), rest.begin() + std::ptrdiff_t(take));
    rest.erase(rest.begin(), rest.begin() + std::ptrdiff_t(take));
    plan.paced = std::uint32_t(take);
  }

  const std::uint64_t allowance = budget_.path_allowance();
  const std::uint32_t samples = options_.samples;
  const std::uint64_t full_probes = allowance / samples;
  std::vector<std::uint32_t> chosen = std::move(mandatory);
  if (full_probes >= chosen.size()) {
    plan.samples = samples;
    const std::size_t take = std::size_t(std::min<std::uint64_t>(full_probes - chosen.size(),
                                                                 rest.size()));
    if (take > 0) {
      auto higher = [&](std::uint32_t a, std::uint32_t b) {
        const ProbePriority &pa = pr.priority[a], &pb = pr.priority[b];
        if (pa < pb || pb < pa) return pb < pa;
        return a < b;
      };
      std::nth_element(rest.begin(), rest.begin() + std::ptrdiff_t(take - 1), rest.end(), higher);
      chosen.insert(chosen.end(), rest.begin(), rest.begin() + std::ptrdiff_t(take));
    }
  } else {
    // Not even the mandatory probes fit at full samples: keep all of them (the max-age
    // promise), each with an equal share of the allowance, but never fewer than min_samples.
    // A --probe-samples below min_samples is itself the floor.
    const std::uint32_t fewest = std::min(options_.min_samples, samples);
    const std::uint64_t share = allowance / chosen.size();
    plan.samples = std::uint32_t(std::clamp<std::uint64_t>(share, fewest, samples));
    plan.over_allowance = share < fewest;
  }
  std::sort(chosen.begin(), chosen.end());  // grid order: neighbouring probes, warm caches

  plan.probes = std::move(chosen);
  plan.hysteresis = options_.blend == BlendRule::per_sample
                        ? options_.hysteresis
                        : sample_equivalent_hysteresis(options_.hysteresis, samples, plan.samples);
  plan.paths = std::uint64_t(plan.probes.size()) * plan.samples;
  plan.predicted_probe_ms = double(plan.paths) * budget_.ms_per_path();
  plan.active = pr.active;
  plan.skipped = pr.active - std::uint32_t(plan.probes.size());
  for (std::uint32_t p : plan.probes) plan.in_view_traced += pr.in_view[p];
  return plan;
}

}  // namespace ddish::probes
