#include "app/xr_frames.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <thread>

#include "gpu/buffer.h"
#include "xr/eye_views.h"

namespace ddish::app {

namespace {

using clock = std::chrono::steady_clock;

double ms_between(clock::time_point a, clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

// How long the session may take to become READY, or to end once asked to.
constexpr auto kStateTimeout = std::chrono::seconds(10);

}  // namespace

XrFrames::XrFrames(xr::Session& session, const display::BaseCamera& origin, std::optional<double> fixed_budget_ms)
    : session_(session), origin_(origin), fixed_budget_ms_(fixed_budget_ms) {}

FrameStart XrFrames::pace(int) {
  const auto deadline = clock::now() + kStateTimeout;
  for (;;) {
    session_.poll_events();
    if (session_.over()) return {.end = true};
    if (!session_.running()) {
      if (clock::now() > deadline)
        throw std::runtime_error("xr: the runtime did not make the session READY within 10 s");
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
      continue;
    }
    xr::Frame f = session_.begin_frame();
    if (session_.over()) return {.end = true};
    if (!f.should_render) {
      session_.end_frame(f, false);
      ++skipped_;
      ++skipped_total_;
      continue;
    }
    for (int e = 0; e < 2; ++e) session_.eye(e).acquire();
    if (session_.over()) return {.end = true};
    pending_ = f;
    const double period_ms = double(f.display_period) * 1e-6;
    XrFrameRecord r;
    r.period_ms = period_ms;
    r.wait_ms = f.wait_ms;
    r.budget_ms = fixed_budget_ms_.value_or(period_ms);
    r.skipped_before = skipped_;
    skipped_ = 0;
    last_ = r;
    FrameStart start;
    if (!fixed_budget_ms_) start.budget_ms = period_ms;
    return start;
  }
}

std::vector<scene::View> XrFrames::views() const {
  if (!pending_) throw std::logic_error("xr: views asked for outside a frame");
  std::vector<scene::View> v;
  for (int e = 0; e < 2; ++e) {
    const XrView& located = pending_->views[static_cast<std::size_t>(e)];
    scene::View view = xr::eye_view(origin_, located.pose, located.fov, static_cast<int>(session_.eye(e).width()),
                                    static_cast<int>(session_.eye(e).height()));
    view.name = e == 0 ? "left" : "right";
    v.push_back(std::move(view));
  }
  return v;
}

void XrFrames::after_batch(VkCommandBuffer cmd, const raster::BatchViews& batch) {
  for (std::uint32_t v = 0; v < batch.count; ++v) {
    const int eye = static_cast<int>(batch.first_view + v);
    if (eye > 1) throw std::logic_error("xr: more than two views rendered");
    session_.eye(eye).record_copy(cmd, batch.display.handle(), batch.display_offset(v));
  }
}

void XrFrames::submit(int frame) {
  if (!pending_) throw std::logic_error("xr: submit outside a frame");
  for (int e = 0; e < 2; ++e) session_.eye(e).release();
  session_.end_frame(*pending_, true);
  const auto now = clock::now();
  XrFrameRecord& r = *last_;
  r.frame = frame;
  r.frame_ms = ms_between(pending_->waited, now);
  r.pose_to_submit_ms = ms_between(pending_->located, now);
  tally_.add(r);
  pending_.reset();
}

void XrFrames::finish() {
  const auto deadline = clock::now() + kStateTimeout;
  if (!session_.over() && !session_.exit_requested()) session_.request_exit();
  while (!session_.over()) {
    session_.poll_events();
    if (session_.over()) break;
    if (clock::now() > deadline) throw std::runtime_error("xr: the runtime did not end the session within 10 s of the request");
    if (session_.running()) {
      const xr::Frame f = session_.begin_frame();
      if (!session_.over()) session_.end_frame(f, false);
    } else {
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
  }
}

const XrFrameRecord& XrFrames::last() const {
  if (!last_) throw std::logic_error("xr: no frame rendered yet");
  return *last_;
}

nlohmann::ordered_json xr_record_json(const XrFrameRecord& r) {
  return {{"frame", r.frame},
          {"predicted_display_period_ms", r.period_ms},
          {"wait_ms", r.wait_ms},
          {"budget_ms", r.budget_ms},
          {"frame_ms", r.frame_ms},
          {"pose_to_submit_ms", r.pose_to_submit_ms},
          {"within_period", r.within_period()},
          {"skipped_before", r.skipped_before}};
}

void XrFrameTally::add(const XrFrameRecord& r) {
  ++rendered;
  if (r.within_period()) ++within_period;
  const double bin = std::max(0.0, r.pose_to_submit_ms) / kBinMs;
  latency_bins[std::min<std::size_t>(latency_bins.size() - 1, static_cast<std::size_t>(bin))] += 1;
}

double XrFrameTally::median_latency_ms() const {
  if (rendered == 0) return 0.0;
  // The upper median, as the sorted list's element rendered / 2 was before.
  const std::uint64_t rank = static_cast<std::uint64_t>(rendered) / 2;
  std::uint64_t seen = 0;
  for (std::size_t b = 0; b < latency_bins.size(); ++b) {
    seen += latency_bins[b];
    if (seen > rank) return (static_cast<double>(b) + 0.5) * kBinMs;
  }
  return static_cast<double>(latency_bins.size()) * kBinMs;
}

}  // namespace ddish::app
