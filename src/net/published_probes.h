// The server side of the change-driven probe stream: what every subscriber holds, and the delta
// that brings them to the volume's current state.
//
// A probe is re-sent when one of its coefficients moved more than
//   max(threshold × max_c |c_00,c|, floor)
// since the value it was last sent from (the fp32 source, not the decoded copy: a probe that
// is not traced is never re-sent for its own rounding). A subscriber's probe therefore differs
// from the server's by at most that amount plus the encoding's error (probe_encoding.h).
// threshold 0 and floor 0: every probe whose coefficients changed at all is sent. With distance
// moments (a volume of moment resolution R > 0), a probe's moment map is sent when it moved by
// more than `moment_threshold` since the map last sent, by moment_map_change's measure (the root
// mean square over the texels of the change of mean distance and spread, fractions of the
// range; 0: any change), when the probe is sent for the first time since it was inactive, and
// when its relocation offset changed; a probe sent with its map is sent with its coefficients and
// offset too, one re-sent for its coefficients alone carries no map (the subscribers keep the one
// they hold, within the threshold of the server's). The threshold is over the map, not a texel:
// at 64 paths a probe an 8x8 map gets about one path a texel and update, so some texel of almost
// every map moves by 1 % of the range every update, while the map as a whole moves far less
// (docs/protocol.md has the figures: the bytes against the client's image error).
//
// A stream may carry a subset of the grid's probes (a brick, bricks.h): then its frames list
// only those, and its keyframes say nothing of the others.
// Probes that were never sent or became inactive are not held: a keyframe lists only the held
// probes with their records (the others are inactive for the client) and, as deactivated, the
// probes found inside geometry; a delta announces a probe that became inactive once, with its
// flags, never its coefficients (a probe never sent is announced only when found inside
// geometry or with a relocation offset: a plain inactive one at its grid position, left out say,
// is what an unlisted probe already is). Inactive probes' offsets travel too: the shader weighs
// all 8 probes of a cell, active or not, before it folds the weights. The snapshot (a keyframe of the last
// published frame) is built from the exact bytes that were sent, so a late joiner holds what
// every other subscriber holds and later deltas keep the same bound for it.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "net/probe_frame.h"
#include "probes/probe_volume.h"

namespace ddish::net {

struct StreamOptions {
  Encoding encoding = Encoding::kCompact;
  bool zstd = false;
  int zstd_level = 3;
  float threshold = 0.0f;  // relative to the probe's largest L0 channel
  float floor = 0.0f;      // absolute, in the coefficients' units
  // A probe's moment map goes again when moment_map_change (below) since the map last sent
  // exceeds this (a fraction of the moment range).
  float moment_threshold = 0.0f;
};

// How far apart two moment maps of one probe are for the Chebyshev test: the root mean square,
// over the texels, of the change of the mean distance mu = m1 and of the spread
// sigma = sqrt(m2 - m1^2), both fractions of the moment range. Zero only for maps whose
// texels all hold the same (mu, sigma).
float moment_map_change(std::span<const glm::vec2> a, std::span<const glm::vec2> b);

struct PublishStats {
  std::uint32_t sent = 0;         // probes with coefficients in the delta
  std::uint32_t maps = 0;         // ... of which with their moment map
  std::uint32_t deactivated = 0;  // probes announced inactive
  std::uint32_t held_back = 0;    // changed, but within the threshold
  std::uint32_t saturated = 0;    // probes the encoding could not represent exactly
  std::size_t bytes = 0;          // of the message
};

class PublishedProbes {
 public:
  // stream_id: this server run's (probe_frame.h), drawn at random at start. `probes`
  // (increasing): the only probes this stream carries, a brick's (bricks.h); empty: all of them.
  // `volume` gives the grid, the SH order and the moment resolution and range of every frame.
  PublishedProbes(const probes::ProbeVolume& volume, std::uint64_t scene_id,
                  std::uint64_t stream_id, const StreamOptions& options,
                  std::vector<std::uint32_t> probes = {});

  // Frame `frame` (> the last published one): the delta from the last published frame to
  // `volume` (same grid, order and moment resolution). server_time_us: when its probe update
  // ended.
  std::vector<std::uint8_t> publish(const probes::ProbeVolume& volume, std::uint64_t frame,
                                    std::int64_t server_time_us, double scene_time,
                                    PublishStats* stats = nullptr);

  // A keyframe of what subscribers hold after the last published frame (frame 0, empty, before
  // the first publish).
  std::vector<std::uint8_t> snapshot() const;

  // An empty keyframe of this stream (no probes): its header describes the stream (grid, SH
  // order, moment resolution and range) for a client that sizes its volume before it takes any
  // frame (the server's INFO reply, probe_server.h).
  std::vector<std::uint8_t> description() const;

  std::uint64_t frame() const { return header_.frame; }
  std::uint32_t held_probes() const;
  const StreamOptions& options() const { return options_; }

 private:
  FrameHeader header_;  // of the last published frame
  StreamOptions options_;
  int coefficient_count_;
  std::size_t sh_bytes_;
  std::size_t map_bytes_;
  std::size_t texels_;
  std::uint32_t grid_probes_ = 0;
  std::vector<std::uint32_t> probes_;     // the probes carried (grid indices, increasing)
  std::vector<std::uint8_t> held_;        // per probe: 1 while subscribers hold it
  std::vector<std::uint8_t> held_coefficients_;  // per probe: the coefficients' bytes last sent
  std::vector<std::uint8_t> held_maps_;   // per probe: the moment map's bytes last sent
  std::vector<glm::vec3> source_;         // per probe: the coefficients they were sent from
  std::vector<glm::vec2> source_moments_; // per probe: the moments its map was sent from
  std::vector<glm::vec3> held_offsets_;   // per probe: the offset last sent
  std::vector<std::uint8_t> announced_;   // per probe not held: the flags subscribers hold
  std::vector<glm::vec3> announced_offsets_;  // ... and the offset
};

}  // namespace ddish::net
