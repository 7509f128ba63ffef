#include "app/render_timings.h"

#include <stdexcept>

#include "io/atomic_file.h"

namespace ddish::app {

double raster_ms(const metrics::FrameTimings& t) {
  return t.stage_ms("raster_record") + t.stage_ms("shadow_gpu") + t.stage_ms("forward_gpu") +
         t.stage_ms("tonemap_gpu") + t.stage_ms("raster_wait") + t.stage_ms("readback");
}

nlohmann::ordered_json render_timings_json(const metrics::TimingLog& log,
                                           const std::vector<FrameCounts>& counts,
                                           const display::ViewSet& set) {
  if (counts.size() != log.frames().size())
    throw std::invalid_argument("timings and counts disagree on the number of frames");
  nlohmann::ordered_json doc;
  doc["display"] = {{"name", set.name},
                    {"kind", display::to_string(set.kind)},
                    {"views", set.size()},
                    {"columns", set.layout.columns},
                    {"rows", set.layout.rows},
                    {"tile_width", set.layout.tile_width},
                    {"tile_height", set.layout.tile_height}};
  doc["per_view_method"] =
      "frame milliseconds / views: the renderer times the forward pass of all views together";
  nlohmann::ordered_json timing = log.to_json();
  nlohmann::ordered_json& frames = timing["frames"];
  for (std::size_t k = 0; k < counts.size(); ++k) {
    const FrameCounts& c = counts[k];
    const metrics::FrameTimings& t = log.frames()[k];
    const double views = c.views > 0 ? double(c.views) : 1.0;
    nlohmann::ordered_json& f = frames[k];
    f["views"] = c.views;
    f["probe_updates"] = c.probe_updates;
    f["probe_rays"] = c.probe_rays;
    f["probes_traced"] = c.probes_traced;
    f["probes_changed"] = c.probes_changed;
    f["probes_uploaded"] = c.probes_uploaded;
    f["probes_active"] = c.probes_active;
    f["probes_inactive"] = c.probes_inactive;
    f["probes_never_updated"] = c.probes_never_updated;
    f["oldest_probe_age"] = c.oldest_probe_age;
    f["probes_unclassified"] = c.probes_unclassified;
    f["raster_passes"] = {{"shadow", c.shadow_passes},
                          {"shadows_reused", c.shadows_reused},
                          {"forward", c.forward_passes},
                          {"tonemap", c.tonemap_passes}};
    f["scheduler"] = c.schedule.to_json();
    f["per_view_ms"] = {{"forward_gpu", t.stage_ms("forward_gpu") / views},
                        {"raster", raster_ms(t) / views}};
    if (c.stream) {
      const StreamFrameCounts& st = *c.stream;
      f["stream"] = {{"synced", st.synced},
                     {"server_frame", st.server_frame},
                     {"stale_ms", st.stale_ms},
                     {"probe_age_ms", st.probe_age_ms ? nlohmann::ordered_json(*st.probe_age_ms)
                                                      : nlohmann::ordered_json(nullptr)},
                     {"bytes_received", st.bytes_received},
                     {"frames_applied", st.frames_applied},
                     {"rejected", st.rejected}};
    }
  }
  doc["frames"] = std::move(frames);
  doc["summary"] = std::move(timing["summary"]);
  return doc;
}

void write_render_timings(const std::filesystem::path& path, const metrics::TimingLog& log,
                          const std::vector<FrameCounts>& counts, const display::ViewSet& set) {
  io::write_file_atomically(path, render_timings_json(log, counts, set).dump(2) + '\n');
}

}  // namespace ddish::app
