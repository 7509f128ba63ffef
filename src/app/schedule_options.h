// The probe scheduling options of `ddish render`: --schedule uniform|visibility, --budget-ms MS
// (the whole frame; default the display profile's per-frame budget, else none), --max-age N
// (frames an active probe may go without an update) and --blend per-update|per-sample (default
// per-sample for visibility, per-update, the published rule, for uniform), and the
// probes::SchedulerOptions and probes::UpdateOptions they make.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "app/probe_options.h"
#include "probes/probe_tracer.h"
#include "probes/scheduler.h"

namespace CLI {
class App;
}

namespace ddish::app {

struct ScheduleArgs {
  std::string schedule = "visibility";
  std::optional<double> budget_ms;     // 0: none, even when the profile has one
  std::optional<long long> max_age;    // frames; default probes::PriorityOptions::max_age
  std::string blend;                   // empty: by schedule
};

// Registers --schedule, --budget-ms, --max-age and --blend on cmd.
void add_schedule_options(CLI::App& cmd, ScheduleArgs& args);

// Throws std::invalid_argument with one line for an unknown schedule or blend rule, a negative
// or non-finite budget or a max age below 1.
void check_schedule_options(const ScheduleArgs& args);

// The frame budget in ms: --budget-ms, else the profile's (profile_budget_ms), else 0 (none).
double frame_budget_ms(const ScheduleArgs& args, std::optional<double> profile_budget_ms);

probes::BlendRule blend_rule(const ScheduleArgs& args);

probes::SchedulerOptions scheduler_options(const ScheduleArgs& args, const ProbeArgs& probe,
                                           double budget_ms);

// The probe tracer's options for a frame planned at `samples` per probe with `hysteresis`,
// blending with the rule of args (S = --probe-samples for the per-sample rule).
probes::UpdateOptions frame_update_options(const ScheduleArgs& args, const ProbeArgs& probe,
                                           std::uint32_t samples, float hysteresis);

}  // namespace ddish::app
