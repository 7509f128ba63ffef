// One message of the probe stream: a fixed 100-byte header and a payload of probe indices,
// coefficients, distance-moment maps and relocation offsets (docs/protocol.md is the full
// description). Little-endian, no padding:
//   offset size field
//        0    4 magic "DDPF"
//        4    2 u16 protocol version (kProtocolVersion, 2)
//        6    1 u8 kind: 0 keyframe (every active probe; the others are inactive), 1 delta
//        7    1 u8 encoding: 0 fp16, 1 shared exponent, 2 compact (probe_encoding.h)
//        8    1 u8 SH order 1..4
//        9    1 u8 flags: bit 0 payload compressed with zstd; other bits zero
//       10    1 u8 moment resolution R: a probe's distance-moment map has R x R texels
//                   (probes/moment_map.h); 0: none, the client interpolates without visibility
//       11    1 u8 reserved, zero
//       12   12 u32 grid counts x, y, z (>= 1, product <= 2^24)
//       24    8 u64 scene identity (geometry and probe grid, app/scene_identity.h)
//       32    8 u64 stream: drawn at random when a server starts, so a restarted server's
//                   frames are never taken for the old one's
//       40    8 u64 server frame: the server's probe update this message carries
//       48    8 u64 base frame: a delta applies to a client holding this frame of this
//                   stream; a keyframe's base frame is its own frame
//       56    8 i64 server time, microseconds of the server's steady clock, when this frame's
//                   probe update ended
//       64    8 f64 scene time, seconds (the animation clock)
//       72    4 f32 moment range, metres (ProbeVolume::moment_range; 0 when R is 0)
//       76    4 u32 updated probes (coefficients in this message)
//       80    4 u32 deactivated probes (deltas only: probes that became inactive)
//       84    4 u32 relocated probes: updated or deactivated probes whose offset is not zero
//       88    4 u32 mapped probes: updated probes whose moment map is in this message (0 when R
//                   is 0; a keyframe's are all its updated probes, so a client's state is
//                   complete after it; a delta's others keep the map the client holds)
//       92    4 u32 payload bytes as sent (after the header; the message is exactly 100 + this)
//       96    4 u32 payload bytes uncompressed (equal to the above without zstd)
//   payload: updated probe indices, deactivated probe indices, relocated probe indices (a
//   subset of the first two), mapped probe indices (a subset of the updated), each an
//   increasing list sent as LEB128 varints of the gaps (first index, then index - previous - 1);
//   one flag byte per deactivated probe (bit 0 set, bit 1 inside geometry, nothing else); per
//   updated probe, in index order, its coefficients, probe_bytes(encoding, order); per mapped
//   probe, in index order, its moment map, moment_bytes(R^2): per texel an fp16 mean distance
//   and an fp16 mean squared distance, / range (or range^2), in [0, 1]; then per relocated
//   probe its offset from its grid position, 3 f32 metres.
//   An updated or deactivated probe that is not relocated has a zero offset (an inactive
//   probe's offset matters too: the shader weighs all 8 probes of a cell before it folds the
//   weights). Nothing after.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "net/probe_encoding.h"
#include "scene/aabb.h"

namespace ddish::net {

inline constexpr char kFrameMagic[4] = {'D', 'D', 'P', 'F'};
inline constexpr std::uint16_t kProtocolVersion = 2;
inline constexpr std::size_t kFrameHeaderBytes = 100;
// The moment resolutions a frame may announce (probes::kMaxMomentResolution).
inline constexpr int kMaxWireMomentResolution = 16;
inline constexpr std::uint32_t kMaxGridProbes = 1u << 24;  // probes::ProbeGrid::kMaxProbes
inline constexpr std::uint8_t kFrameFlagZstd = 1u << 0;
// Deactivated probes' flag byte (the bits of probes::ProbeFlag): inactive, inside geometry.
inline constexpr std::uint8_t kWireFlagInactive = 1u << 0;
inline constexpr std::uint8_t kWireFlagInsideGeometry = 1u << 1;

enum class FrameKind : std::uint8_t { kKeyframe = 0, kDelta = 1 };

struct FrameHeader {
  FrameKind kind = FrameKind::kKeyframe;
  Encoding encoding = Encoding::kHalf;
  int sh_order = 2;
  bool zstd = false;
  std::uint32_t counts[3] = {1, 1, 1};
  std::uint64_t scene_id = 0;
  std::uint64_t stream_id = 0;
  std::uint64_t frame = 0;
  std::uint64_t base_frame = 0;
  std::int64_t server_time_us = 0;
  double scene_time = 0.0;
  int moment_resolution = 0;  // R; 0: no moments
  float moment_range = 0.0f;  // metres; 0 when moment_resolution is 0

  std::uint32_t probe_count() const { return counts[0] * counts[1] * counts[2]; }
  int moment_texels() const { return moment_resolution * moment_resolution; }
};
// Bytes of one updated probe's coefficients, and of one mapped probe's moment map (2 R^2 halves).
std::size_t coefficient_bytes(const FrameHeader& header);
std::size_t map_bytes(const FrameHeader& header);

// A decoded message, or the parts of one to encode.
struct ProbeFrame {
  FrameHeader header;
  std::vector<std::uint32_t> updated;        // increasing probe indices
  std::vector<glm::vec3> coefficients;       // updated.size() × (order+1)^2, probe after probe
  std::vector<std::uint32_t> deactivated;    // increasing, disjoint from `updated`
  std::vector<std::uint8_t> deactivated_flags;  // one per deactivated probe
  std::vector<std::uint32_t> mapped;         // increasing, a subset of `updated` (all of it in a keyframe)
  std::vector<glm::vec2> moments;            // mapped.size() × R^2 (mean d, mean d^2) / range
  std::vector<std::uint32_t> relocated;      // increasing, a subset of updated ∪ deactivated
  std::vector<glm::vec3> offsets;            // one per relocated probe, finite, not zero, metres
};

// The parts of a message as a server keeps them, already encoded, in index order:
// coefficients holds updated.size() × coefficient_bytes(header) bytes, maps mapped.size() ×
// map_bytes(header).
struct FrameParts {
  std::span<const std::uint32_t> updated;
  std::span<const std::uint8_t> coefficients;
  std::span<const std::uint32_t> mapped;
  std::span<const std::uint8_t> maps;
  std::span<const std::uint32_t> deactivated;
  std::span<const std::uint8_t> deactivated_flags;
  std::span<const std::uint32_t> relocated;
  std::span<const glm::vec3> offsets;
};

// Why a message was rejected. Every kind has a name for the log and a counter on the client.
enum class RejectKind : std::uint8_t {
  kTruncated,        // shorter than its header or than the payload it announces
  kBadMagic,         // not a probe frame
  kBadVersion,       // another protocol version
  kBadHeader,        // unknown kind, encoding, order or flags; reserved bits; empty/huge grid
  kSizeMismatch,     // sizes that do not add up (extra bytes, counts beyond the grid, ...)
  kBadIndex,         // an index out of the grid, not increasing, or both updated and deactivated
  kBadCoefficients,  // Inf, NaN or a code no encoder writes
  kDecompression,    // zstd failed, or its size differs from the header's
  kSceneMismatch,    // well formed, but of another scene, grid, order or moment map (the client's)
  kBadVisibility,    // a moment outside [0, 1] or not finite; a mapped probe not updated; a
                     // keyframe without the map of one of its probes; an offset not finite, zero,
                     // of a probe neither updated nor deactivated, or (the client's check) beyond
                     // kMaxRelocation cells
};
inline constexpr int kRejectKindCount = 10;
std::string reject_name(RejectKind kind);

struct DecodeLimits {
  // Largest uncompressed payload accepted (a zstd bomb or a lying header stops here).
  std::size_t max_payload_bytes = std::size_t(256) << 20;
};

struct DecodeResult {
  bool ok = false;
  RejectKind reject = RejectKind::kTruncated;
  std::string detail;  // one line: what was wrong
  ProbeFrame frame;
};

// Checks everything before trusting it: on any inconsistency the result says which and why,
// and `frame` is not to be used.
DecodeResult decode_frame(std::span<const std::uint8_t> message, const DecodeLimits& limits = {});

// Assembles a message from already encoded probe records (what a server keeps of what it
// sent). zstd per header.zstd at `zstd_level`.
std::vector<std::uint8_t> encode_frame(const FrameHeader& header, const FrameParts& parts,
                                       int zstd_level = 3);

// Encodes frame.coefficients and frame.moments itself; `saturated` (optional) counts the probes
// whose values could not be represented exactly (probe_encoding.h).
std::vector<std::uint8_t> encode_frame(const ProbeFrame& frame, std::uint32_t* saturated = nullptr,
                                       int zstd_level = 3);

// The header alone (for peeking at kind, frames and identity); false when the message is too
// short or not a probe frame of this version. decode_frame is the only full check.
bool peek_header(std::span<const std::uint8_t> message, FrameHeader& header);

// The probe grid's bounds as the server placed them: the third part of its INFO reply
// (probe_server.h), 6 f32 (the minimum corner, then the maximum; metres). A client whose grid
// counts are the server's takes them as its own, so a grid that `serve --probe-placement fit`
// moved is the client's too without a fit of its own (which could pick another offset in a near
// tie on another machine, and be refused by the scene identity).
inline constexpr std::size_t kGridBoundsBytes = 24;
std::vector<std::uint8_t> encode_grid_bounds(const scene::Aabb& bounds);
// False unless exactly kGridBoundsBytes of finite values with min <= max on every axis and a
// finite extent (max - min); `bounds` is then left as it was.
bool decode_grid_bounds(std::span<const std::uint8_t> bytes, scene::Aabb& bounds);

}  // namespace ddish::net
