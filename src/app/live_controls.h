// The live window's part of `ddish render`'s frame loop (app/live_window.h has the window
// itself): between frames the events are read and the switches applied — indirect light (the
// renderer draws the probes or an empty volume, and the probe update pauses), the schedule
// (uniform ⇄ visibility), the probe-grid overlay — and the frame's views are made from the
// window's camera, the light-field focal plane at its orbit distance. The window's close or
// Ctrl-C raise stop(), the frame loop's stop flag in window mode. Also the status line.
#pragma once

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "app/frame_loop.h"
#include "app/live_window.h"
#include "app/view_options.h"
#include "probes/probe_volume.h"

namespace ddish::probes {
class Scheduler;
}

namespace ddish::app {

class LiveControls {
 public:
  // Everything is borrowed. `volume` is the probe source's; `scheduler` null for remote probes
  // (no schedule switch).
  LiveControls(LiveWindow& live, raster::Renderer& renderer, const probes::ProbeVolume& volume,
               probes::Scheduler* scheduler, bool no_indirect, const char* tag);

  // Once per frame, as the loop's view source.
  std::vector<scene::View> frame_views(const scene::Scene& posed, const DisplayChoice& choice,
                                       const DisplayArgs& display, const CameraArgs& camera);

  // Called before the volume is uploaded whole (indirect light switched back on): brings its
  // values up to date where the probe tracer keeps them on the GPU (ProbeEngine::read_back).
  void set_volume_reader(std::function<void()> read_back) { read_back_ = std::move(read_back); }

  const std::atomic<bool>& stop() const { return stop_; }
  const bool& indirect() const { return indirect_; }  // SwitchableProbes reads it
  // The window title and status text of a frame: the display (title only), probes / raster /
  // present milliseconds, views, the oldest probe's age in frames and the switches. The text:
  //   PROBES 12.3  RASTER 45.6  PRESENT 0.8 MS
  //   48 VIEWS  PROBE AGE 3  INDIRECT ON  VISIBILITY  GRID
  // (UNIFORM or VISIBILITY: the schedule, REMOTE PROBES from a server; GRID: the overlay is on).
  LiveStatus status(const std::string& display, const FrameReport& report, double present_ms) const;

 private:
  LiveWindow& live_;
  raster::Renderer& renderer_;
  const probes::ProbeVolume& volume_;
  std::function<void()> read_back_;
  const probes::ProbeVolume dark_;  // what "indirect off" draws: no probe has light yet
  probes::Scheduler* scheduler_;
  bool no_indirect_;
  const char* tag_;
  std::atomic<bool> stop_{false};
  bool indirect_;
  bool overlay_ = false;
};

}  // namespace ddish::app
