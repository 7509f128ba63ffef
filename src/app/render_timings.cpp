#include "app/render_timings.h"

#include <stdexcept>

#include "io/atomic_file.h"

namespace ddish::app {

double raster_ms(const metrics::FrameTimings& t) {
  return t.stage_ms("raster_record") + t.stage_ms("shadow_gpu") + t.stage_ms("forward_gpu") +
         t.stage_ms("tonemap_gpu") + t.stage_ms("raster_wait") + t.stage_ms("readback");
}

nlohmann::ordered_json timings_head_json(const display::ViewSet& set) {
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
  return doc;
}

nlohmann::ordered_json frame_record_json(const metrics::FrameTimings& t, const FrameCounts& c) {
  const double views = c.views > 0 ? double(c.views) : 1.0;
  nlohmann::ordered_json f = metrics::frame_json(t);
  f["views"] = c.views;
  f["probe_updates"] = c.probe_updates;
  f["probe_rays"] = c.probe_rays;
  f["probes_traced"] = c.probes_traced;
  f["probes_changed"] = c.probes_changed;
  f["probes_uploaded"] = c.probes_uploaded;
  f["probes_imported"] = c.probes_imported;
  f["probes_active"] = c.probes_active;
  f["probes_inactive"] = c.probes_inactive;
  f["probes_never_updated"] = c.probes_never_updated;
  f["oldest_probe_age"] = c.oldest_probe_age;
  f["probes_unclassified"] = c.probes_unclassified;
  f["raster_passes"] = {{"shadow", c.shadow_passes},
                        {"shadows_reused", c.shadows_reused},
                        {"forward", c.forward_passes},
                        {"tonemap", c.tonemap_passes}};
  f["read_back"] = c.read_back;
  f["rendered_again"] = c.rendered_again;
  f["scheduler"] = c.schedule.to_json();
  f["resources"] = {{"rss_kb", c.resources.rss_kb},
                    {"open_fds", c.resources.open_fds},
                    {"gpu_allocations", c.resources.gpu_allocations},
                    {"gpu_bytes", c.resources.gpu_bytes}};
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
  return f;
}

TimingsFile::TimingsFile(const std::filesystem::path& path, const display::ViewSet& set) : file_(path) {
  std::string head = timings_head_json(set).dump(2);
  // The head object without its closing brace, then the frames array as it grows.
  head.erase(head.find_last_not_of("}\n ") + 1);
  file_.write(head);
  file_.write(",\n  \"frames\": [");
}

void TimingsFile::add(const metrics::FrameTimings& t, const FrameCounts& c, nlohmann::ordered_json extra) {
  flush_held();
  held_ = Held{t, c, std::move(extra)};
}

metrics::FrameTimings* TimingsFile::last() { return held_ ? &held_->timings : nullptr; }

void TimingsFile::flush_held() {
  if (!held_) return;
  summary_.add(held_->timings);
  file_.write(frames_ == 0 ? "\n    " : ",\n    ");
  nlohmann::ordered_json record = frame_record_json(held_->timings, held_->counts);
  if (held_->extra.is_object())
    for (const auto& [key, value] : held_->extra.items()) record[key] = value;
  file_.write(record.dump());
  ++frames_;
  held_.reset();
}

void TimingsFile::finish() {
  flush_held();
  std::string tail = frames_ == 0 ? "],\n" : "\n  ],\n";
  tail += "  \"summary\": " + summary_.to_json().dump();
  tail += "\n}\n";
  file_.write(tail);
  file_.commit();
}

}  // namespace ddish::app
