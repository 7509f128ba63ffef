// The per-frame orchestration of `ddish render`: pose the scene at t = time + k / fps, follow
// the moved instances in the path tracer, update the probes once (shared by every view), upload
// the probes that changed, rasterize the views, and write the images that are asked for. Each
// stage's milliseconds go into a metrics::FrameTimings per frame:
//   pose, tracer_update (animated scenes), probe_update, upload, raster_record (CPU: frame data
//   and command recording), shadow_gpu / forward_gpu / tonemap_gpu (GPU timestamps), raster_wait
//   (the rest of the wait for the GPU: submission, resolve, copies), readback, output.
// They do not overlap, so a frame's total_ms is its wall time; rasterization is
// raster_record + the three *_gpu + raster_wait. All N views of a frame go to the renderer in
// one call, after the one probe update they share.
//
// The probe update follows the scheduler (probes/scheduler.h): each frame it plans which active
// probes to trace and with how many samples from this frame's views and its budget, the tracer
// runs ONCE on that list, and the scheduler then observes what the whole frame cost. Only the
// probes that changed (traced, or found inside geometry) are uploaded; the renderer made the
// first, full upload of the volume itself. Inactive probes are never traced nor uploaded.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "metrics/timing.h"
#include "probes/probe_tracer.h"
#include "probes/scheduler.h"
#include "probes/scheduler_record.h"
#include "scene/view.h"

namespace ddish::probes {
class ProbeVolume;
}  // namespace ddish::probes

namespace ddish::raster {
class Renderer;
struct FrameOutput;
}  // namespace ddish::raster

namespace ddish::scene {
struct Scene;
}

namespace ddish::trace {
class Tracer;
}

namespace ddish::app {

struct FrameLoopOptions {
  int frames = 1;
  double time = 0.0;  // t of frame 0, seconds
  double fps = 30.0;
  bool every = false;             // write every frame, not only the last
  bool update_probes = true;      // false: render with the probes as they are
  // > 0 (--loop): the scene time wraps at this period (the animation's duration), so an
  // animation plays again and again instead of holding its last pose.
  double loop_period = 0.0;
};

// What a frame did, counted (not timed): the figures that must not grow with the views.
struct FrameCounts {
  std::uint32_t views = 0;
  // Probe tracer runs this frame, read from the volume's update counter (ProbeVolume::frame()),
  // not from the loop's own control flow: one per frame whatever the number of views.
  std::uint64_t probe_updates = 0;
  std::uint64_t probe_rays = 0;  // rays the path tracer cast this frame (probe paths)
  std::uint32_t probes_traced = 0;
  std::uint32_t probes_changed = 0;   // traced or newly inactive: what the loop hands over
  std::uint32_t probes_uploaded = 0;  // what the renderer copied (it may copy the whole volume
                                      // when many changed: ProbeTextures::kFullUploadFraction)
  std::uint32_t probes_active = 0;     // after this frame's update
  std::uint32_t probes_inactive = 0;   // inside geometry (or otherwise inactive) after it
  std::uint32_t probes_never_updated = 0;  // active probes no update has reached yet
  std::uint32_t oldest_probe_age = 0;      // the largest age of an active probe after it
  std::uint32_t probes_unclassified = 0;   // not yet traced, so not yet known inside or out
  std::uint32_t shadow_passes = 0;     // raster::FrameStats::shadow_passes
  bool shadows_reused = false;
  std::uint32_t forward_passes = 0;
  std::uint32_t tonemap_passes = 0;
  // The scheduler's log of this frame (budget, stages, probes traced and skipped, samples,
  // rays); with update_probes off only its stages and budget are filled.
  probes::SchedulerFrameRecord schedule;
};

struct FrameReport {
  int frame = 0;
  double t = 0.0;
  FrameCounts counts;
  const metrics::FrameTimings* timings = nullptr;
};

struct FrameLoopResult {
  metrics::TimingLog timings;
  std::vector<FrameCounts> counts;  // one per frame
  std::vector<std::filesystem::path> written;
};

// The views of a frame from the scene as posed (a camera node may be animated).
using ViewSource = std::function<std::vector<scene::View>(const scene::Scene&)>;

// The probe tracer's options for a frame's plan (samples, hysteresis and the blend rule).
using UpdateOptionsFor = std::function<probes::UpdateOptions(const probes::FramePlan&)>;

// Writes frame `frame`'s images and returns the files written.
using FrameSink =
    std::function<std::vector<std::filesystem::path>(int frame, const raster::FrameOutput&)>;

class FrameLoop {
 public:
  // Everything is borrowed and must outlive the loop; the renderer was made for `volume`.
  FrameLoop(scene::Scene& scene, trace::Tracer& tracer, probes::ProbeTracer& probe_tracer,
            probes::Scheduler& scheduler, UpdateOptionsFor update_options,
            probes::ProbeVolume& volume, raster::Renderer& renderer, ViewSource views);

  // Runs the frames; `sink` (optional) gets the last frame, or every frame with options.every;
  // `progress` (optional) is called after each frame.
  FrameLoopResult run(const FrameLoopOptions& options, const FrameSink& sink = {},
                      const std::function<void(const FrameReport&)>& progress = {});

 private:
  // The probes traced this frame (`traced`, increasing) and those whose flags changed since the
  // last upload (found inside geometry), merged in increasing order.
  std::vector<std::uint32_t> changed_probes(const std::vector<std::uint32_t>& traced);

  scene::Scene& scene_;
  trace::Tracer& tracer_;
  probes::ProbeTracer& probe_tracer_;
  probes::Scheduler& scheduler_;
  UpdateOptionsFor update_options_;
  probes::ProbeVolume& volume_;
  raster::Renderer& renderer_;
  ViewSource views_;
  std::vector<std::uint8_t> last_flags_;  // probe flags at the last upload
};

}  // namespace ddish::app
