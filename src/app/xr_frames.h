// `ddish xr`'s parts of the one frame loop (DESIGN.md, "one frame loop, three seams"), over an
// xr::Session:
//   - the pacer: drives the session's state machine (xrPollEvent), waits for each frame
//     (xrWaitFrame, xrBeginFrame), ends the frames the runtime does not want rendered
//     (shouldRender false) with no layer, locates the eyes at the predicted display time,
//     acquires both swapchain images and gives the frame's budget: the predicted display period
//     (the scheduler takes from it the measured rest of the frame, probes/budget.h);
//   - the view source: the located eyes as scene::Views (xr/eye_views.h);
//   - the GPU sink: after_batch copies each eye's tonemapped view into its swapchain image; the
//     frame sink releases the images and ends the frame with a projection layer of the located
//     poses and FOVs.
// Each rendered frame's record: period, wait, budget, the app's frame time (xrWaitFrame's
// return to xrEndFrame's), and the pose-to-submit latency (xrLocateViews' return to xrEndFrame's).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/frame_loop.h"
#include "display/view_set.h"
#include "raster/render_request.h"
#include "xr/session.h"

namespace ddish::app {

struct XrFrameRecord {
  int frame = 0;
  double period_ms = 0.0;       // predictedDisplayPeriod
  double wait_ms = 0.0;         // xrWaitFrame blocked
  double budget_ms = 0.0;       // handed to the scheduler (0: none)
  double frame_ms = 0.0;        // xrWaitFrame returned -> xrEndFrame returned
  double pose_to_submit_ms = 0.0;  // xrLocateViews returned -> xrEndFrame returned
  int skipped_before = 0;       // frames not rendered (shouldRender false) since the last one
  bool within_period() const { return frame_ms <= period_ms; }
};
// A record as the --timings file holds it (the "xr" member of each frame).
nlohmann::ordered_json xr_record_json(const XrFrameRecord& r);

// What the end-of-run summary needs of every rendered frame, in a fixed size however long the
// session: a headset runs for hours at 90 Hz, so no per-frame record is kept.
struct XrFrameTally {
  static constexpr double kBinMs = 0.1;  // the median's resolution
  int rendered = 0;
  int within_period = 0;
  // Pose-to-submit latencies in kBinMs bins up to 1 s; the last bin holds everything longer.
  std::array<std::uint32_t, 10001> latency_bins{};
  void add(const XrFrameRecord& r);
  double median_latency_ms() const;  // the bin's centre; 0 before the first frame
};

class XrFrames {
 public:
  // `fixed_budget_ms`: set (--budget-ms), the scheduler's budget stays that and the display
  // period is only recorded.
  XrFrames(xr::Session& session, const display::BaseCamera& origin, std::optional<double> fixed_budget_ms);

  FrameStart pace(int frame);
  std::vector<scene::View> views() const;
  void after_batch(VkCommandBuffer cmd, const raster::BatchViews& batch);
  void submit(int frame);
  // After the loop: asks the runtime to end a session still running, and follows it to EXITING
  // (ending frames without layers meanwhile). Throws std::runtime_error when it never ends.
  void finish();

  // The newest rendered frame's record (complete after submit()); throws before the first.
  const XrFrameRecord& last() const;
  const XrFrameTally& tally() const { return tally_; }
  int skipped() const { return skipped_total_; }

 private:
  xr::Session& session_;
  display::BaseCamera origin_;
  std::optional<double> fixed_budget_ms_;
  std::optional<xr::Frame> pending_;
  std::optional<XrFrameRecord> last_;
  XrFrameTally tally_;
  int skipped_ = 0;
  int skipped_total_ = 0;
};

}  // namespace ddish::app
