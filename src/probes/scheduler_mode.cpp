#include "probes/scheduler_mode.h"

#include <stdexcept>

namespace ddish::probes {

const char* schedule_mode_name(ScheduleMode mode) {
  switch (mode) {
    case ScheduleMode::uniform: return "uniform";
    case ScheduleMode::visibility: return "visibility";
  }
  return "visibility";
}

ScheduleMode parse_schedule_mode(const std::string& name) {
  if (name == "uniform") return ScheduleMode::uniform;
  if (name == "visibility") return ScheduleMode::visibility;
  throw std::invalid_argument("unknown schedule '" + name + "' (uniform or visibility)");
}

}  // namespace ddish::probes
