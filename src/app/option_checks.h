// The option checks that render, view and xr share, run before any scene loads: one bad option
// is one error line and costs no scene load.
#pragma once

#include <string>

#include "app/camera_options.h"
#include "app/lighting_options.h"
#include "app/probe_options.h"
#include "app/schedule_options.h"
#include "app/warmup_options.h"

namespace ddish::app {

// Throws std::invalid_argument naming the first bad option.
void check_frame_options(const ProbeArgs& probe, const ScheduleArgs& schedule,
                         const WarmupOptions& warmup, const LightingArgs& lighting,
                         const CameraArgs& camera, const std::string& tonemap);

}  // namespace ddish::app
