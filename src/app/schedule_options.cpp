#include "app/schedule_options.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "probes/scheduler_mode.h"

namespace ddish::app {

void add_schedule_options(CLI::App& cmd, ScheduleArgs& a) {
  cmd.add_option("--schedule", a.schedule,
                 "which probes each frame updates: uniform (all active) or visibility (by the "
                 "views, the probes' ages and the budget)")
      ->capture_default_str();
  cmd.add_option("--budget-ms", a.budget_ms,
                 "whole-frame time budget in ms (default: the display profile's, else none; "
                 "0: none)");
  cmd.add_option("--max-age", a.max_age,
                 fmt::format("frames an active probe may go without an update (default {})",
                             probes::PriorityOptions{}.max_age));
  cmd.add_option("--blend", a.blend,
                 "blend rule: per-update or per-sample (default: per-sample for visibility, "
                 "per-update for uniform)");
}

void check_schedule_options(const ScheduleArgs& a) {
  probes::parse_schedule_mode(a.schedule);
  if (!a.blend.empty()) probes::parse_blend_rule(a.blend);
  if (a.budget_ms && !(std::isfinite(*a.budget_ms) && *a.budget_ms >= 0.0))
    throw std::invalid_argument(
        fmt::format("--budget-ms must be 0 (none) or a positive number of ms, got {:g}",
                    *a.budget_ms));
  if (a.max_age && (*a.max_age < 1 || *a.max_age > 1000000))
    throw std::invalid_argument(
        fmt::format("--max-age must be between 1 and 1000000 frames, got {}", *a.max_age));
}

double frame_budget_ms(const ScheduleArgs& a, std::optional<double> profile_budget_ms) {
  if (a.budget_ms) return *a.budget_ms;
  return profile_budget_ms.value_or(0.0);
}

probes::BlendRule blend_rule(const ScheduleArgs& a) {
  if (!a.blend.empty()) return probes::parse_blend_rule(a.blend);
  return probes::parse_schedule_mode(a.schedule) == probes::ScheduleMode::uniform
             ? probes::BlendRule::per_update
             : probes::BlendRule::per_sample;
}

probes::SchedulerOptions scheduler_options(const ScheduleArgs& a, const ProbeArgs& probe,
                                           double budget_ms) {
  probes::SchedulerOptions so;
  so.mode = probes::parse_schedule_mode(a.schedule);
  so.samples = static_cast<std::uint32_t>(probe.samples);
  so.min_samples = std::min(so.min_samples, so.samples);
  so.hysteresis = probe.hysteresis;
  so.blend = blend_rule(a);
  if (a.max_age) so.priority.max_age = static_cast<std::uint32_t>(*a.max_age);
  so.budget.budget_ms = budget_ms;
  probes::check_scheduler_options(so);
  return so;
}

probes::UpdateOptions frame_update_options(const ScheduleArgs& a, const ProbeArgs& probe,
                                           std::uint32_t samples, float hysteresis) {
  probes::UpdateOptions u = update_options(probe);
  u.samples = samples;
  u.hysteresis = hysteresis;
  u.blend = blend_rule(a);
  u.reference_samples = static_cast<std::uint32_t>(probe.samples);
  return u;
}

}  // namespace ddish::app
