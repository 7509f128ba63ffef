// One frame of the scheduler's log: the budget, what each stage took, and what the probe
// update did (probes traced and skipped, samples per probe, paths and rays), as a plain struct
// with a JSON form the frame loop writes beside its timings.
//
// JSON form:
//   {"frame": 12, "mode": "visibility", "budget_ms": 33.3, "frame_ms": 31.9, "within_budget": true,
//    "stages_ms": {"probe_update": 12.1, "raster": 18.0, ...},
//    "probes": {"active": 900, "in_view": 400, "traced": 250, "in_view_traced": 230,
//               "skipped": 650, "overdue": 0, "paced": 30, "samples_per_probe": 256,
//               "newly_inactive": 0},
//    "paths": 64000, "rays": 180000, "hysteresis": 0.95,
//    "probe_ms_allowance": 12.5, "headroom_ms": 2.1, "predicted_probe_ms": 12.3, "ms_per_path": 1.9e-4,
//    "mrays_per_second": 14.8, "over_allowance": false}
// budget_ms and within_budget are null without a budget; probe_ms_allowance and headroom_ms
// (the jitter margin the controller kept below the budget when it planned the frame,
// probes/budget.h) are null then too.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "probes/budget.h"
#include "probes/probe_tracer.h"
#include "probes/scheduler.h"

namespace ddish::probes {

struct StageMs {
  std::string name;
  double ms = 0.0;
};

struct SchedulerFrameRecord {
  std::int64_t frame = 0;
  ScheduleMode mode = ScheduleMode::visibility;
  double budget_ms = 0.0;  // 0: none
  double frame_ms = 0.0;
  std::vector<StageMs> stages;  // in the frame loop's order

  std::uint32_t active = 0;
  std::uint32_t in_view = 0;
  std::uint32_t traced = 0;           // probes the update traced (UpdateStats::probes_traced)
  std::uint32_t in_view_traced = 0;
  std::uint32_t skipped = 0;          // active probes left out this frame
  std::uint32_t overdue = 0;
  std::uint32_t paced = 0;
  std::uint32_t samples_per_probe = 0;
  std::uint32_t newly_inactive = 0;
  std::uint64_t paths = 0;
  std::uint64_t rays = 0;
  float hysteresis = 0.0f;

  double probe_ms_allowance = 0.0;  // inf: none
  double headroom_ms = 0.0;         // the controller's jitter margin at planning time
  double predicted_probe_ms = 0.0;
  double ms_per_path = 0.0;         // the controller's estimate after this frame
  double mrays_per_second = 0.0;    // smoothed
  bool over_allowance = false;

  bool within_budget() const { return budget_ms <= 0.0 || frame_ms <= budget_ms; }
  nlohmann::json to_json() const;
};

// The record of a frame from its plan, the update's statistics and the measured stages
// (frame_ms is their sum), read after Scheduler::observe so the rates include this frame.
SchedulerFrameRecord make_frame_record(std::int64_t frame, const FramePlan& plan,
                                       const UpdateStats& update, std::vector<StageMs> stages,
                                       const BudgetController& budget);

}  // namespace ddish::probes
