#include "probes/scheduler_record.h"

#include <cmath>

namespace ddish::probes {

nlohmann::json SchedulerFrameRecord::to_json() const {
  nlohmann::json stages_ms = nlohmann::json::object();
  for (const StageMs& s : stages) stages_ms[s.name] = s.ms;
  const bool budgeted = budget_ms > 0.0;
  // JSON has no infinity: an unlimited allowance is null, like a missing budget.
  auto finite_or_null = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); };
  return {
      {"frame", frame},
      {"mode", schedule_mode_name(mode)},
      {"budget_ms", budgeted ? nlohmann::json(budget_ms) : nlohmann::json()},
      {"frame_ms", frame_ms},
      {"within_budget", budgeted ? nlohmann::json(within_budget()) : nlohmann::json()},
      {"stages_ms", stages_ms},
      {"probes",
       {{"active", active},
        {"in_view", in_view},
        {"traced", traced},
        {"in_view_traced", in_view_traced},
        {"skipped", skipped},
        {"overdue", overdue},
        {"paced", paced},
        {"samples_per_probe", samples_per_probe},
        {"newly_inactive", newly_inactive}}},
      {"paths", paths},
      {"rays", rays},
      {"hysteresis", hysteresis},
      {"probe_ms_allowance", budgeted ? finite_or_null(probe_ms_allowance) : nlohmann::json()},
      {"headroom_ms", budgeted ? nlohmann::json(headroom_ms) : nlohmann::json()},
      {"predicted_probe_ms", predicted_probe_ms},
      {"ms_per_path", ms_per_path},
      {"mrays_per_second", mrays_per_second},
      {"over_allowance", over_allowance},
  };
}

SchedulerFrameRecord make_frame_record(std::int64_t frame, const FramePlan& plan,
                                       const UpdateStats& update, std::vector<StageMs> stages,
                                       const BudgetController& budget) {
  SchedulerFrameRecord r;
  r.frame = frame;
  r.mode = plan.mode;
  r.budget_ms = plan.budget_ms;
  for (const StageMs& s : stages) r.frame_ms += s.ms;
  r.stages = std::move(stages);
  r.active = plan.active;
  r.in_view = plan.in_view;
  r.traced = update.probes_traced;
  r.in_view_traced = plan.in_view_traced;
  r.skipped = plan.skipped;
  r.overdue = plan.overdue;
  r.paced = plan.paced;
  r.samples_per_probe = plan.samples;
  r.newly_inactive = update.newly_inactive;
  r.paths = update.paths;
  r.rays = update.rays;
  r.hysteresis = plan.hysteresis;
  r.probe_ms_allowance = plan.probe_ms_allowance;
  r.headroom_ms = plan.headroom_ms;
  r.predicted_probe_ms = plan.predicted_probe_ms;
  r.ms_per_path = budget.ms_per_path();
  r.mrays_per_second = budget.mrays_per_second();
  r.over_allowance = plan.over_allowance;
  return r;
}

}  // namespace ddish::probes
