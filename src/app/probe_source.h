// The probe seam of the frame loop (DESIGN.md, "one frame loop, three seams"): where a frame's
// probes come from. The loop poses the scene, asks the source to bring its volume up to date for
// the frame's views, uploads what the source says changed, rasterizes and writes; the source
// then hears what the whole frame cost.
//   - InProcessProbes (here): the scheduler plans, the probe tracer updates once, the probes
//     traced or newly inactive changed (the path of `ddish render`, and of `ddish serve`
//     without a renderer);
//   - RemoteProbes (remote_probes.h): the probe stream's client (`ddish view`).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "app/frame_counts.h"
#include "app/tracer_choice.h"
#include "metrics/timing.h"
#include "probes/probe_tracer.h"
#include "probes/scheduler.h"
#include "raster/probe_import.h"
#include "scene/view.h"

namespace ddish::probes {
class ProbeVolume;
}
namespace ddish::scene {
struct Scene;
}

namespace ddish::app {

// The warm-up before the first visible frame ("no blotchy first seconds"): every active probe
// traced at the frame's full sample count, round after round, until each has `samples` samples
// or the time bound is reached. A round is never cut short, so the bound is kept to within one
// round (a round is started only while the last one's duration still fits), and the first round
// always runs.
struct WarmupOptions {
  std::uint32_t samples = 2048;  // per probe, the goal
  double max_ms = 2000.0;        // the time bound; <= 0: no warm-up
  bool enabled() const { return max_ms > 0.0 && samples > 0; }
};

struct WarmupReport {
  int rounds = 0;
  double ms = 0.0;
  std::uint32_t probes = 0;             // active probes after the warm-up
  std::uint64_t samples_per_probe = 0;  // rounds * samples of a round
  bool bounded = false;                 // stopped by the time bound before the goal
  std::vector<std::uint32_t> changed;   // probes to upload (increasing)
};

// A frame's probe update: what changed (for the upload), and the plan and statistics of an
// in-process update (empty otherwise) for the frame's scheduler record.
struct ProbeStep {
  std::vector<std::uint32_t> changed;  // increasing probe indices
  probes::FramePlan plan;
  probes::UpdateStats update;
};

class ProbeSource {
 public:
  virtual ~ProbeSource() = default;
  virtual probes::ProbeVolume& volume() = 0;
  // After the scene was posed for the frame (`moved`: the instances that moved).
  virtual void posed(const scene::Scene& scene, const std::vector<int>& moved,
                     metrics::FrameTimings& timings) = 0;
  // The frame's probe update for these views (`enabled` false: the probes stay as they are);
  // stages go into `timings`, figures into `counts`.
  virtual ProbeStep update(const std::vector<scene::View>& views, bool enabled,
                           metrics::FrameTimings& timings, FrameCounts& counts) = 0;
  // This frame's whole budget, from a view source with a clock of its own (OpenXR's display
  // period: FrameLoopOptions::pacer), before update(). A source that plans nothing itself (the
  // stream's client: the server schedules) ignores it.
  virtual void set_frame_budget(double /*budget_ms*/) {}
  // Before the first frame, the scene posed for it: bring the probes close to converged
  // (WarmupOptions). A source whose probes come from elsewhere (the stream's client: its first
  // frame waits for the server's snapshot) does nothing.
  virtual WarmupReport warm_up(const WarmupOptions& /*options*/) { return {}; }
  // Where the loop takes the changed probes from: the volume's values (uploaded from the CPU),
  // or, from a probe tracer that keeps them on the renderer's device (ProbeEngine's hand-off),
  // the averages there, which the renderer converts on the device; volume() is then behind
  // until read_back().
  virtual std::optional<raster::GpuProbeData> gpu_probes() { return std::nullopt; }
  // Brings volume()'s coefficients and moments up to date, for a reader of the CPU values.
  virtual void read_back() {}
  // After the frame (frame index, its stages): the source learns what it cost, and fills the
  // frame's scheduler record.
  virtual void finished(int frame, const metrics::FrameTimings& timings, const ProbeStep& step,
                        bool enabled, FrameCounts& counts) = 0;
};

// The probe tracer's options for a frame's plan (samples, hysteresis and the blend rule).
using UpdateOptionsFor = std::function<probes::UpdateOptions(const probes::FramePlan&)>;

class InProcessProbes final : public ProbeSource {
 public:
  // Everything is borrowed and must outlive the source.
  InProcessProbes(ProbeEngine& engine, probes::Scheduler& scheduler, UpdateOptionsFor update_options,
                  probes::ProbeVolume& volume);

  probes::ProbeVolume& volume() override { return volume_; }
  void posed(const scene::Scene& scene, const std::vector<int>& moved,
             metrics::FrameTimings& timings) override;
  ProbeStep update(const std::vector<scene::View>& views, bool enabled,
                   metrics::FrameTimings& timings, FrameCounts& counts) override;
  void finished(int frame, const metrics::FrameTimings& timings, const ProbeStep& step,
                bool enabled, FrameCounts& counts) override;
  void set_frame_budget(double budget_ms) override { scheduler_.set_budget_ms(budget_ms); }
  WarmupReport warm_up(const WarmupOptions& options) override;
  std::optional<raster::GpuProbeData> gpu_probes() override { return engine_.gpu_probes(); }
  void read_back() override { engine_.read_back(volume_); }

 private:
  // The probes traced this frame (`traced`, increasing) and those whose flags changed since the
  // last upload (found inside geometry), merged in increasing order.
  std::vector<std::uint32_t> changed_probes(const std::vector<std::uint32_t>& traced);

  ProbeEngine& engine_;
  probes::ProbeUpdater& probe_tracer_;
  probes::Scheduler& scheduler_;
  UpdateOptionsFor update_options_;
  probes::ProbeVolume& volume_;
  std::vector<std::uint8_t> last_flags_;  // probe flags at the last upload
};

}  // namespace ddish::app
