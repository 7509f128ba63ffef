// The per-frame orchestration of `ddish render` and `ddish view`: pose the scene at
// t = time + k / fps, let the probe source (probe_source.h: in-process, or the probe stream's
// client) follow the moved instances and bring the probes up to date once (shared by every
// view), upload the probes that changed, rasterize the views, and write the images that are
// asked for. Each
// stage's milliseconds go into a metrics::FrameTimings per frame:
//   pose, tracer_update (animated scenes), probe_update, upload, raster_record (CPU: frame data
//   and command recording), shadow_gpu / forward_gpu / tonemap_gpu (GPU timestamps), raster_wait
//   (the rest of the wait for the GPU: submission, resolve, copies), readback (0 for a frame
//   the sink does not write: only written frames come back to the CPU), output (the sink's
//   time: for `render`, handing the views to the writer thread, app/output_queue.h).
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

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/frame_counts.h"
#include "app/probe_source.h"
#include "metrics/timing.h"
#include "probes/probe_tracer.h"
#include "probes/scheduler.h"
#include "probes/scheduler_record.h"
#include "raster/render_request.h"
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

// What a view source with a clock of its own says as a frame starts: OpenXR's xrWaitFrame
// blocks until the frame is due and gives its display period, which becomes the frame's budget
// (the live window's vsync could do the same). The pacer's own wait is not a stage of the frame.
struct FrameStart {
  bool end = false;                 // no frame: the loop ends before this one (the session ended)
  std::optional<double> budget_ms;  // this frame's whole budget for the probe scheduler
};
using FramePacer = std::function<FrameStart(int frame)>;

struct FrameLoopOptions {
  int frames = 1;
  double time = 0.0;  // t of frame 0, seconds
  double fps = 30.0;
  int every = 0;                  // the sink gets frames k with (k + 1) % every == 0 (0: only the last)
  bool update_probes = true;      // false: render with the probes as they are
  // Checked once per frame, before its output: when raised, the frame is written as the last
  // one and the loop ends (Ctrl-C, app/interrupt.h). Null: never stops early.
  const std::atomic<bool>* stop = nullptr;
  // > 0 (--loop): the scene time wraps at this period (the animation's duration), so an
  // animation plays again and again instead of holding its last pose.
  double loop_period = 0.0;
  // Handed to the renderer every frame: a GPU sink (the window's swapchain, OpenXR's) records
  // its copies after each batch and may leave the pixels on the GPU (raster/render_request.h).
  // Its read_back says whether any frame needs its pixels on the CPU; which ones do is below.
  raster::RenderRequest render_request;
  // Which of the frames the sink gets need their pixels read back (files to write): asked
  // before the frame renders, `last` true for the run's last frame (the last of `frames`, or
  // the stop already raised). Null: every frame the sink gets. The other frames' pixels stay
  // on the GPU: reading back and converting a 48-view 420x560 frame took 63-194 ms on
  // lavapipe (under load 6-10). A stop raised while a frame renders unread makes it the last: it is
  // rendered again and read back (its raster stages count both renders, FrameCounts).
  std::function<bool(int frame, bool last)> read_back;
  // Set: called before each frame (before the scene is posed); `frames` is then the most frames.
  FramePacer pacer;
  // Before the first frame (and the first pacer call: OpenXR's time between READY and the
  // first frame), the probe source's warm-up; not a stage of any frame. Off: max_ms = 0.
  WarmupOptions warmup{.samples = 0, .max_ms = 0.0};
};

struct FrameReport {
  int frame = 0;
  double t = 0.0;
  FrameCounts counts;
  const metrics::FrameTimings* timings = nullptr;
  const WarmupReport* warmup = nullptr;  // frame 0: the warm-up before it (rounds 0: none ran)
};

// What a run did. Nothing per frame is kept (a run of hours must not grow): the progress callback
// sees each frame's timings and counts, and writes them where they are wanted (TimingsFile).
struct FrameLoopResult {
  std::size_t frames = 0;  // frames done
  std::vector<std::filesystem::path> written;
  bool stopped = false;  // ended early by FrameLoopOptions::stop; `frames` were done
  WarmupReport warmup;  // rounds == 0: none ran
  bool paced_out = false;  // ended by the pacer (FrameStart::end) before `frames` frames
};

// The views of a frame from the scene as posed (a camera node may be animated).
using ViewSource = std::function<std::vector<scene::View>(const scene::Scene&)>;

// Writes frame `frame`'s images and returns the files written. The frame is the sink's: it may
// move the images out (the loop reads only its stats, before the sink runs).
using FrameSink =
    std::function<std::vector<std::filesystem::path>(int frame, raster::FrameOutput&)>;

class FrameLoop {
 public:
  // Everything is borrowed and must outlive the loop; the renderer was made for the source's
  // volume.
  FrameLoop(scene::Scene& scene, ProbeSource& probes, raster::Renderer& renderer, ViewSource views);
  // The in-process probe source (`ddish render`) over these parts.
  FrameLoop(scene::Scene& scene, ProbeEngine& engine, probes::Scheduler& scheduler, UpdateOptionsFor update_options,
            probes::ProbeVolume& volume, raster::Renderer& renderer, ViewSource views);

  // Runs the frames; `sink` (optional) gets the last frame, or every options.every-th;
  // `progress` (optional) is called after each frame.
  FrameLoopResult run(const FrameLoopOptions& options, const FrameSink& sink = {},
                      const std::function<void(const FrameReport&)>& progress = {});

 private:
  scene::Scene& scene_;
  std::unique_ptr<ProbeSource> owned_probes_;  // the in-process source the loop made itself
  ProbeSource& probes_;
  raster::Renderer& renderer_;
  ViewSource views_;
};

}  // namespace ddish::app
