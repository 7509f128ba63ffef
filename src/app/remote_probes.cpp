#include "app/remote_probes.h"

namespace ddish::app {

RemoteProbes::RemoteProbes(const net::ClientOptions& options, probes::ProbeVolume& volume,
                           std::uint64_t scene_id, int first_wait_ms, int frame_wait_ms)
    : volume_(volume),
      client_(options, volume, scene_id),
      first_wait_ms_(first_wait_ms),
      frame_wait_ms_(frame_wait_ms) {}

ProbeStep RemoteProbes::update(const std::vector<scene::View>& views, bool enabled,
                               metrics::FrameTimings& timings, FrameCounts& counts) {
  ProbeStep step;
  StreamFrameCounts stream;
  if (enabled) {
    metrics::StageTimer timer(timings, "probe_receive");
    client_.send_views(views);
    // The first frame waits for every needed brick (the snapshots of every server), later ones
    // for the next frame that brings probes.
    const net::ClientPoll poll = client_.poll(first_ ? first_wait_ms_ : frame_wait_ms_, first_);
    step.changed = poll.changed;
    stream.bytes_received = poll.bytes;
    stream.frames_applied = poll.frames_applied;
  }
  first_ = false;
  stream.synced = client_.synced();
  stream.server_frame = client_.server_frame();
  stream.stale_ms = client_.stale_ms();
  stream.probe_age_ms = client_.probe_age_ms();
  stream.rejected = client_.rejected_total();
  counts.stream = stream;
  return step;
}

void RemoteProbes::finished(int frame, const metrics::FrameTimings& timings, const ProbeStep& step,
                            bool, FrameCounts& counts) {
  std::vector<probes::StageMs> stages;
  for (const metrics::StageTime& s : timings.stages) stages.push_back({s.name, s.ms});
  counts.schedule = probes::make_frame_record(frame, step.plan, step.update, std::move(stages), no_budget_);
}

}  // namespace ddish::app
