// The --timings JSON of `ddish render`: metrics::TimingLog's per-frame stage milliseconds and
// summary, plus what the stages cannot say on their own:
//   "display": {"name", "kind", "views", "columns", "rows", "tile_width", "tile_height"}
//   "per_view_method": how per-view times are derived
//   and in every frame: "views", "probe_updates" (probe tracer runs, counted from the volume's
//   update counter), "probe_rays", "probes_traced", "probes_changed" (traced or newly
//   inactive: what the loop hands the renderer), "probes_uploaded" (what the renderer copied,
//   the whole volume when many changed), "probes_imported" (what it converted on the GPU instead,
//   from a probe tracer's averages on its device: the GPU-resident hand-off), "probes_active",
//   "probes_inactive", "probes_never_updated", "oldest_probe_age", "probes_unclassified"
//   (after the update), "raster_passes": {"shadow", "shadows_reused", "forward", "tonemap"}
//   (raster::FrameStats), "read_back" (the views came back to the CPU: only the frames that
//   are written do), "rendered_again" (a stop came while the frame rendered unread: it was
//   drawn a second time to be read back and written as the last), "scheduler" (probes::SchedulerFrameRecord's JSON: budget, stages,
//   probes traced / skipped, samples per probe, rays, over_allowance), and "per_view_ms":
//   {"forward_gpu": forward_gpu / views, "raster": (raster_record + shadow_gpu + forward_gpu +
//   tonemap_gpu + raster_wait + readback) / views}; for `ddish view` also "stream":
//   {"synced", "server_frame", "stale_ms", "probe_age_ms" (null until the server's clock is
//   known), "bytes_received", "frames_applied", "rejected"} (app/frame_counts.h); and
//   "resources": {"rss_kb", "open_fds", "gpu_allocations", "gpu_bytes"}, sampled after the
//   frame (app/process_resources.h).
// The renderer times the forward pass of all views with one pair of timestamps (blocks of views
// share passes under multiview), so per-view figures are the frame's time divided by the views.
// The file is written as the frames come (TimingsFile): nothing per frame is kept in memory, so a
// run of hours (a live window, a headset) stays flat; a stopped run's file holds the frames done.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>

#include <nlohmann/json.hpp>

#include "app/frame_counts.h"
#include "display/view_set.h"
#include "io/atomic_file.h"
#include "metrics/timing.h"

namespace ddish::app {

// Raster milliseconds of a frame: every stage the rasterizer's frame costs.
double raster_ms(const metrics::FrameTimings& frame);

// The document's head ("display", "per_view_method") and one frame's record.
nlohmann::ordered_json timings_head_json(const display::ViewSet& set);
nlohmann::ordered_json frame_record_json(const metrics::FrameTimings& t, const FrameCounts& c);

// The --timings file of render, view and xr, written whole or not at all (io::AtomicFileWriter).
// Throws std::runtime_error "cannot write FILE: REASON" from any call that writes.
class TimingsFile {
 public:
  TimingsFile(const std::filesystem::path& path, const display::ViewSet& set);

  // A frame's record. The newest one is held back until the next (or finish()), so that a stage
  // measured after the loop (the output writer's drain) can still be added to it through last().
  // `extra`'s members (OpenXR's record of the frame) join the frame's record.
  void add(const metrics::FrameTimings& t, const FrameCounts& c, nlohmann::ordered_json extra = {});
  metrics::FrameTimings* last();  // the held frame, nullptr before the first
  // Writes the held frame and the summary, and renames the file into place.
  void finish();

 private:
  struct Held {
    metrics::FrameTimings timings;
    FrameCounts counts;
    nlohmann::ordered_json extra;
  };
  void flush_held();

  io::AtomicFileWriter file_;
  metrics::StageSummary summary_;
  std::optional<Held> held_;
  std::size_t frames_ = 0;
};

}  // namespace ddish::app
