// The client side of the probe stream: a probe volume that follows the server's frames.
//
// A keyframe replaces the whole state (its probes active with their coefficients, every other
// probe inactive); a delta applies only to the frame it was made from (its base frame), so a
// client never mixes states: an older frame is dropped (the Clone pattern's "updates older than
// the snapshot"), and a delta from a frame the client does not hold says that a snapshot is
// needed. A keyframe of another stream (a restarted server) is taken whatever its frame number,
// and keeps the active probes the client holds that it does not carry (not traced yet by the new
// server) until the new stream sends them; a delta of another stream is a gap. Frames of another
// scene or grid, or with probes outside the mirror's (another brick's), are never applied.
#pragma once

#include <cstdint>
#include <vector>

#include "net/probe_frame.h"
#include "probes/probe_volume.h"

namespace ddish::net {

enum class ApplyOutcome {
  kApplied,
  kOld,            // not newer than what the mirror holds: dropped
  kGap,            // a delta from a frame the mirror does not hold: take a snapshot
  kSceneMismatch,  // another scene identity, grid, SH order or moment map: refused
  kOutside,        // a probe outside the mirror's probes (another brick's): refused
  kBadOffset,      // a relocation offset beyond kMaxRelocation cells of this grid: refused
};

class ProbeMirror {
 public:
  // `volume` (borrowed) is the client's own volume of its scene; scene_id its identity.
  // `probes` (increasing): the probes this mirror follows, a brick's (bricks.h), whose
  // keyframes leave every other probe alone; empty: all of them.
  ProbeMirror(probes::ProbeVolume& volume, std::uint64_t scene_id,
              std::vector<std::uint32_t> probes = {});

  // Applies a decoded frame (nothing of it unless it is applied whole); `changed` receives the
  // probes whose coefficients, moments, offsets or flags it set (increasing), for the
  // renderer's upload. An updated probe takes its coefficients, its offset (zero unless the
  // frame lists it relocated) and, when the frame lists it mapped, its moment map (otherwise it
  // keeps the map it holds; a keyframe maps all its probes, decode_frame checks); a deactivated
  // one is zeroed, its moments reset and its offset zero, with the frame's inside-geometry flag.
  ApplyOutcome apply(const ProbeFrame& frame, std::vector<std::uint32_t>& changed);

  // Whether a keyframe has been applied, and the server frame held (valid once synced).
  bool synced() const { return synced_; }
  std::uint64_t frame() const { return frame_; }
  std::uint64_t stream() const { return stream_; }
  // Probes the last keyframe left as they were (a restarted server had not sent them yet).
  std::uint32_t kept() const { return kept_; }
  // Forgets the held frame, keeping the probes (after a lost server: the next keyframe,
  // whatever its frame number, is taken).
  void desync() { synced_ = false; }

  // Whether the frame's scene identity, grid, order, moment resolution and moment range are the
  // mirror's volume's.
  bool matches(const FrameHeader& header) const;

 private:
  probes::ProbeVolume& volume_;
  std::uint64_t scene_id_;
  std::vector<std::uint32_t> probes_;  // followed, increasing
  std::vector<std::uint8_t> mine_;     // per grid probe: 1 when followed
  bool synced_ = false;
  std::uint64_t frame_ = 0;
  std::uint64_t stream_ = 0;
  std::uint32_t kept_ = 0;
};

}  // namespace ddish::net
