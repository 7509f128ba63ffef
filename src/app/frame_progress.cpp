#include "app/frame_progress.h"

#include <algorithm>
#include <cstdio>
#include <string>

#include <fmt/format.h>

#include "app/render_timings.h"

namespace ddish::app {

void print_progress(const FrameReport& r, int frames) {
  const metrics::FrameTimings& t = *r.timings;
  const FrameCounts& c = r.counts;
  const probes::SchedulerFrameRecord& sr = c.schedule;
  const std::string budget =
      sr.budget_ms > 0.0 ? fmt::format(" of budget {:g} ms{}", sr.budget_ms,
                                       sr.within_budget() ? "" : " (over)")
                         : std::string();
  std::fprintf(stderr,
               "frame %d/%d t=%.3f s: %u views; probes %.1f ms (%llu update, %u of %u active "
               "traced at %u samples, %u changed, %u %s in %.1f ms), raster %.1f ms = %.2f ms/view "
               "(GPU shadow %.1f + forward %.1f + tonemap %.1f), output %.1f ms, total %.1f "
               "ms%s\n",
               r.frame + 1, frames, r.t, c.views, t.stage_ms("probe_update"),
               static_cast<unsigned long long>(c.probe_updates), c.probes_traced,
               c.probe_updates > 0 ? sr.active : c.probes_active, sr.samples_per_probe,
               c.probes_changed, c.probes_imported > 0 ? c.probes_imported : c.probes_uploaded,
               c.probes_imported > 0 ? "converted on the GPU" : "uploaded", t.stage_ms("upload"),
               raster_ms(t), raster_ms(t) / std::max(1u, c.views), t.stage_ms("shadow_gpu"),
               t.stage_ms("forward_gpu"), t.stage_ms("tonemap_gpu"), t.stage_ms("output"),
               t.total_ms(), budget.c_str());
  if (c.stream)
    std::fprintf(stderr, "  stream: received in %.1f ms; %s frame %llu, stale %.0f ms, probe age %s, %llu bytes, %u frames, %llu rejected\n",
                 t.stage_ms("probe_receive"), c.stream->synced ? "server" : "last probes of",
                 static_cast<unsigned long long>(c.stream->server_frame),
                 c.stream->stale_ms,
                 c.stream->probe_age_ms ? fmt::format("{:.1f} ms", *c.stream->probe_age_ms).c_str() : "unknown",
                 static_cast<unsigned long long>(c.stream->bytes_received), c.stream->frames_applied,
                 static_cast<unsigned long long>(c.stream->rejected));
  if (r.frame == 0 && c.probe_updates > 0)
    std::fprintf(stderr, "render: %u of %u probes inside geometry: never traced or uploaded%s\n",
                 c.probes_inside_geometry, c.probes_active + c.probes_inactive,
                 c.probes_unclassified > 0
                     ? fmt::format(" ({} not classified yet: their first update will tell)",
                                   c.probes_unclassified)
                           .c_str()
                     : "");
}

}  // namespace ddish::app
