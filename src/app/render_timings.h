// The --timings JSON of `ddish render`: metrics::TimingLog's per-frame stage milliseconds and
// summary, plus what the stages cannot say on their own:
//   "display": {"name", "kind", "views", "columns", "rows", "tile_width", "tile_height"}
//   "per_view_method": how per-view times are derived
//   and in every frame: "views", "probe_updates" (probe tracer runs, counted from the volume's
//   update counter), "probe_rays", "probes_traced", "probes_changed" (traced or newly
//   inactive: what the loop hands the renderer), "probes_uploaded" (what the renderer copied,
//   the whole volume when many changed), "probes_active",
//   "probes_inactive", "probes_never_updated", "oldest_probe_age", "probes_unclassified"
//   (after the update), "raster_passes": {"shadow", "shadows_reused", "forward", "tonemap"}
//   (raster::FrameStats), "scheduler" (probes::SchedulerFrameRecord's JSON: budget, stages,
//   probes traced / skipped, samples per probe, rays, over_allowance), and "per_view_ms":
//   {"forward_gpu": forward_gpu / views, "raster": (raster_record + shadow_gpu + forward_gpu +
//   tonemap_gpu + raster_wait + readback) / views}; for `ddish view` also "stream":
//   {"synced", "server_frame", "stale_ms", "probe_age_ms" (null until the server's clock is
//   known), "bytes_received", "frames_applied", "rejected"} (app/frame_counts.h).
// The renderer times the forward pass of all views with one pair of timestamps (blocks of views
// share passes under multiview), so per-view figures are the frame's time divided by the views.
#pragma once

#include <filesystem>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/frame_loop.h"
#include "display/view_set.h"
#include "metrics/timing.h"

namespace ddish::app {

// Raster milliseconds of a frame: every stage the rasterizer's frame costs.
double raster_ms(const metrics::FrameTimings& frame);

nlohmann::ordered_json render_timings_json(const metrics::TimingLog& log,
                                           const std::vector<FrameCounts>& counts,
                                           const display::ViewSet& set);

// Writes render_timings_json; throws std::runtime_error when the file cannot be written.
void write_render_timings(const std::filesystem::path& path, const metrics::TimingLog& log,
                          const std::vector<FrameCounts>& counts, const display::ViewSet& set);

}  // namespace ddish::app
