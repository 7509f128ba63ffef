// The remote probe source of the frame loop (`ddish view`): the probe stream's client
// (net/probe_client.h). Its volume comes from starting_volume (probe_setup.h), sized for the
// server's distance-moment maps; each applied frame sets the probes' coefficients, moments,
// relocation offsets and states, and the probes it changed go to the upload. Each frame it sends the frame's views upstream, takes what the server
// published since the last frame, and hands the probes that changed to the upload. Frame 0
// waits up to `first_wait_ms` for the server's snapshot (every server's, for the bricks the views
// need); without one the volume keeps what it
// was made with (baked probes, or nothing: direct light only) and later frames take the
// snapshot whenever the server appears. Every later frame waits up to `frame_wait_ms` for the
// server's next frame (0: takes what has arrived), which paces a client to its server's ticks. A lost server leaves the probes as they were.
// Per frame it records the stream's figures (FrameCounts::stream): the server frame held,
// stale_ms, the age of the held probes at the hand-over (server trace end -> now, through the
// clock offset of the snapshot replies), bytes and frames received, rejected messages.
#pragma once

#include <cstdint>
#include <memory>

#include "app/probe_source.h"
#include "net/probe_client.h"
#include "probes/budget.h"

namespace ddish::app {

class RemoteProbes final : public ProbeSource {
 public:
  // `volume` (borrowed) holds the starting probes; scene_id: this scene's identity.
  RemoteProbes(const net::ClientOptions& options, probes::ProbeVolume& volume,
               std::uint64_t scene_id, int first_wait_ms, int frame_wait_ms);

  probes::ProbeVolume& volume() override { return volume_; }
  void posed(const scene::Scene&, const std::vector<int>&, metrics::FrameTimings&) override {}
  ProbeStep update(const std::vector<scene::View>& views, bool enabled,
                   metrics::FrameTimings& timings, FrameCounts& counts) override;
  void finished(int frame, const metrics::FrameTimings& timings, const ProbeStep& step,
                bool enabled, FrameCounts& counts) override;

  const net::ProbeClient& client() const { return client_; }

 private:
  probes::ProbeVolume& volume_;
  net::ProbeClient client_;
  int first_wait_ms_;
  int frame_wait_ms_;
  bool first_ = true;
  probes::BudgetController no_budget_{probes::BudgetOptions{}};
};

}  // namespace ddish::app
