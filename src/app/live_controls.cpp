#include "app/live_controls.h"

#include <cstdio>

#include <fmt/format.h>

#include "app/interrupt.h"
#include "app/render_timings.h"
#include "probes/scheduler.h"
#include "raster/renderer.h"

namespace ddish::app {

LiveControls::LiveControls(LiveWindow& live, raster::Renderer& renderer,
                           const probes::ProbeVolume& volume, probes::Scheduler* scheduler,
                           bool no_indirect, const char* tag)
    : live_(live),
      renderer_(renderer),
      volume_(volume),
      dark_(volume.grid(), volume.sh_order(), volume.moment_resolution()),
      scheduler_(scheduler),
      no_indirect_(no_indirect),
      tag_(tag),
      indirect_(!no_indirect) {
  live_.set_tag(tag);
}

std::vector<scene::View> LiveControls::frame_views(const scene::Scene& posed,
                                                   const DisplayChoice& choice,
                                                   const DisplayArgs& display,
                                                   const CameraArgs& camera) {
  live_.pump();
  if (live_.quit() || stop_flag().load()) stop_ = true;
  const LiveSwitches sw = live_.take_switches();
  if (sw.indirect && no_indirect_) {
    std::fprintf(stderr, "%s: I: the run has --no-indirect, its shaders draw no probes\n", tag_);
  } else if (sw.indirect) {
    indirect_ = !indirect_;  // the renderer is idle between frames: swap what it draws with
    if (indirect_ && read_back_) read_back_();
    renderer_.upload_probes(indirect_ ? volume_ : dark_);
    std::fprintf(stderr, "%s: I: indirect light %s\n", tag_, indirect_ ? "on" : "off");
  }
  if (sw.schedule && scheduler_) {
    const auto next = scheduler_->options().mode == probes::ScheduleMode::uniform
                          ? probes::ScheduleMode::visibility
                          : probes::ScheduleMode::uniform;
    scheduler_->set_mode(next);
    std::fprintf(stderr, "%s: U: schedule %s\n", tag_, probes::schedule_mode_name(next));
  }
  if (sw.overlay) {
    overlay_ = !overlay_;
    std::fprintf(stderr, "%s: G: probe-grid overlay %s\n", tag_, overlay_ ? "on" : "off");
  }
  if (sw.status)
    std::fprintf(stderr, "%s: H: status text %s\n", tag_, live_.status_shown() ? "shown" : "hidden");
  DisplayArgs d = display;
  d.focal_distance = live_.focal_distance();
  std::vector<scene::View> views = make_frame_views(posed, choice, d, camera, live_.camera()).views;
  set_probe_overlay(live_, overlay_ ? &volume_ : nullptr, views);
  return views;
}

LiveStatus LiveControls::status(const std::string& display, const FrameReport& r,
                                double present_ms) const {
  const metrics::FrameTimings& t = *r.timings;
  const double raster = raster_ms(t);
  const double probes = t.stage_ms("tracer_update") + t.stage_ms("probe_update") + t.stage_ms("upload");
  const char* schedule = scheduler_ ? probes::schedule_mode_name(scheduler_->options().mode) : "remote probes";
  LiveStatus s;
  s.title = fmt::format(
      "ddish {} · {} views · probes {:.1f} ms · raster {:.1f} ms · present {:.1f} ms · "
      "oldest probe {} frames · indirect {} · {}{}",
      display, r.counts.views, probes, raster, present_ms, r.counts.oldest_probe_age,
      indirect_ ? "on" : "off", schedule, overlay_ ? " · probe grid" : "");
  s.lines.push_back(fmt::format("PROBES {:.1f}  RASTER {:.1f}  PRESENT {:.1f} MS", probes, raster, present_ms));
  s.lines.push_back(fmt::format("{} {}  PROBE AGE {}  INDIRECT {}  {}{}", r.counts.views,
                                r.counts.views == 1 ? "VIEW" : "VIEWS", r.counts.oldest_probe_age,
                                indirect_ ? "ON" : "OFF", schedule, overlay_ ? "  GRID" : ""));
  return s;
}

}  // namespace ddish::app
