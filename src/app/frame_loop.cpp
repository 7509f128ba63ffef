#include "app/frame_loop.h"

#include <algorithm>

#include <fmt/format.h>

#include "metrics/color.h"
#include "metrics/image_io.h"
#include "probes/probe_tracer.h"
#include "probes/probe_volume.h"
#include "raster/renderer.h"
#include "scene/scene.h"
#include "trace/tracer.h"

namespace ddish::app {

namespace {

metrics::Image linear_image(const raster::ViewImage& v) {
  metrics::Image img(v.width, v.height);
  img.pixels() = v.linear;
  return img;
}

// The display pixels as an Image of linear values whose sRGB encoding is exactly those bytes,
// so that metrics::write_png (clamp, sRGB-encode, round) writes them back unchanged.
metrics::Image display_image(const raster::ViewImage& v) {
  metrics::Image img(v.width, v.height);
  for (std::size_t i = 0; i < v.display.size(); ++i) {
    const std::uint32_t p = v.display[i];
    img.pixels()[i] = {metrics::srgb_decode(float(p & 0xffu) / 255.0f),
                       metrics::srgb_decode(float((p >> 8) & 0xffu) / 255.0f),
                       metrics::srgb_decode(float((p >> 16) & 0xffu) / 255.0f)};
  }
  return img;
}

}  // namespace

FrameLoop::FrameLoop(scene::Scene& scene, trace::Tracer& tracer,
                     const probes::ProbeTracer& probe_tracer, probes::ProbeVolume& volume,
                     raster::Renderer& renderer, ViewSource views)
    : scene_(scene),
      tracer_(tracer),
      probe_tracer_(probe_tracer),
      volume_(volume),
      renderer_(renderer),
      views_(std::move(views)) {
  last_flags_.resize(volume.probe_count());
  for (std::uint32_t i = 0; i < volume.probe_count(); ++i) last_flags_[i] = volume.state(i).flags;
}

std::filesystem::path FrameLoop::frame_path(const std::filesystem::path& dir, int frame,
                                            const std::string& extension) {
  return dir / fmt::format("frame_{:04d}.{}", frame, extension);
}

std::vector<std::uint32_t> FrameLoop::changed_probes() {
  // Updated this frame (age back to 0), or whose flags changed (a probe found inside
  // geometry drops out of the interpolation and must be re-sent with weight 0).
  std::vector<std::uint32_t> dirty;
  for (std::uint32_t i = 0; i < volume_.probe_count(); ++i) {
    const probes::ProbeState& s = volume_.state(i);
    if ((s.active() && s.age == 0) || s.flags != last_flags_[i]) dirty.push_back(i);
    last_flags_[i] = s.flags;
  }
  return dirty;
}

FrameLoopResult FrameLoop::run(const FrameLoopOptions& o,
                               const std::function<void(const FrameReport&)>& progress) {
  FrameLoopResult result;
  const bool animated = !scene_.animations.empty();
  for (int k = 0; k < o.frames; ++k) {
    metrics::FrameTimings timings;
    timings.frame = k;
    const double t = o.time + double(k) / o.fps;
    FrameReport report;
    report.frame = k;
    report.t = t;
    std::vector<int> moved;
    {
      metrics::StageTimer timer(timings, "pose");
      moved = scene_.pose(t);
    }
    if (animated) {  // lights may move without any instance moving
      metrics::StageTimer timer(timings, "tracer_update");
      tracer_.update(scene_, moved);
    }
    if (o.update_probes) {
      metrics::StageTimer timer(timings, "probe_update");
      report.probes_traced = probe_tracer_.update(volume_).probes_traced;
    }
    {
      metrics::StageTimer timer(timings, "upload");
      const std::vector<std::uint32_t> dirty = changed_probes();
      report.probes_uploaded = renderer_.upload_probes(volume_, dirty).probes;
    }
    const std::vector<scene::View> views = views_(scene_);
    const raster::FrameOutput frame = renderer_.render(scene_, views);
    // The GPU passes run while the CPU waits for the submission, so the wait is split into the
    // passes' timestamp durations and the rest (submission, resolve and copies, idle): the
    // stages of a frame add up to its wall time.
    const raster::FrameStats& st = frame.stats;
    const double gpu_ms = st.shadow_gpu_ms + st.forward_gpu_ms + st.tonemap_gpu_ms;
    timings.add("raster_record", st.record_ms);
    timings.add("shadow_gpu", st.shadow_gpu_ms);
    timings.add("forward_gpu", st.forward_gpu_ms);
    timings.add("tonemap_gpu", st.tonemap_gpu_ms);
    timings.add("raster_wait", std::max(0.0, st.execute_ms - gpu_ms));
    timings.add("readback", st.readback_ms);
    {
      metrics::StageTimer timer(timings, "output");
      const bool last = k + 1 == o.frames;
      if (last) {
        result.last_linear = linear_image(frame.views.front());
        result.last_display = display_image(frame.views.front());
      }
      if (!o.out.empty() && (o.every || last)) {
        // One view today: frame_NNNN; several views will add a view suffix.
        const metrics::Image linear = last ? result.last_linear : linear_image(frame.views.front());
        const metrics::Image display = last ? result.last_display : display_image(frame.views.front());
        const auto png = frame_path(o.out, k, "png");
        const auto exr = frame_path(o.out, k, "exr");
        metrics::write_png(png, display);
        metrics::write_exr(exr, linear);
        result.written.push_back(png);
        result.written.push_back(exr);
      }
    }
    result.timings.add(timings);
    report.timings = &result.timings.frames().back();
    if (progress) progress(report);
  }
  return result;
}

}  // namespace ddish::app
