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
#include <vector>

#include "app/frame_counts.h"
#include "metrics/timing.h"
#include "probes/probe_tracer.h"
#include "probes/scheduler.h"
#include "scene/view.h"

namespace ddish::probes {
class ProbeVolume;
}
namespace ddish::scene {
struct Scene;
}
namespace ddish::trace {
class Tracer;
}

namespace ddish::app {

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
  InProcessProbes(trace::Tracer& tracer, probes::ProbeTracer& probe_tracer,
                  probes::Scheduler& scheduler, UpdateOptionsFor update_options,
                  probes::ProbeVolume& volume);

  probes::ProbeVolume& volume() override { return volume_; }
  void posed(const scene::Scene& scene, const std::vector<int>& moved,
             metrics::FrameTimings& timings) override;
  ProbeStep update(const std::vector<scene::View>& views, bool enabled,
                   metrics::FrameTimings& timings, FrameCounts& counts) override;
  void finished(int frame, const metrics::FrameTimings& timings, const ProbeStep& step,
                bool enabled, FrameCounts& counts) override;

 private:
  // The probes traced this frame (`traced`, increasing) and those whose flags changed since the
  // last upload (found inside geometry), merged in increasing order.
  std::vector<std::uint32_t> changed_probes(const std::vector<std::uint32_t>& traced);

  trace::Tracer& tracer_;
  probes::ProbeTracer& probe_tracer_;
  probes::Scheduler& scheduler_;
  UpdateOptionsFor update_options_;
  probes::ProbeVolume& volume_;
  std::vector<std::uint8_t> last_flags_;  // probe flags at the last upload
};

}  // namespace ddish::app
