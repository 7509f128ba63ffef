// How the probes of a frame are chosen (--schedule uniform|visibility).
#pragma once

#include <string>

namespace ddish::probes {

enum class ScheduleMode {
  // The published behaviour (DDISH-GI): every active probe, every frame, full samples; no budget.
  uniform,
  // By what the views see, the probes' ages and the frame budget (scheduler.h). The default.
  visibility,
};

const char* schedule_mode_name(ScheduleMode mode);  // "uniform" / "visibility"
// Throws std::invalid_argument naming the choices for anything else.
ScheduleMode parse_schedule_mode(const std::string& name);

}  // namespace ddish::probes
