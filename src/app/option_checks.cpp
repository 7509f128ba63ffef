#include "app/option_checks.h"

#include "raster/tonemap.h"

namespace ddish::app {

void check_frame_options(const ProbeArgs& probe, const ScheduleArgs& schedule,
                         const WarmupOptions& warmup, const LightingArgs& lighting,
                         const CameraArgs& camera, const std::string& tonemap) {
  check_probe_options(probe);
  check_schedule_options(schedule);
  check_warmup_options(warmup);
  sky_radiance(lighting);
  parse_pose(camera.camera);
  raster::parse_tone_curve(tonemap);
}

}  // namespace ddish::app
