// Probe volume files (`ddish probes --out PATH`): the packed volume behind a fixed 64-byte
// header, plus a JSON summary beside it (PATH.json) for people and scripts.
//
// Binary layout, little-endian, no padding:
//   offset  size  field
//        0     4  magic "DDPV"
//        4     4  u32 version (2; version 1 files, which end after the probes, still read)
//        8    12  i32 counts x, y, z (>= 1)
//       20    12  f32 bounds min x, y, z
//       32    12  f32 bounds max x, y, z
//       44     4  u32 SH order (1..4)
//       48     4  u32 encoding: 0 fp16, 1 shared exponent, 2 mixed (see volume_packing.h)
//       52     4  u32 words per probe = 3 (order + 1)^2 + 1 (28 at L2: 56 bytes)
//       56     8  u64 updates the volume had received when it was written
//       64     -  probes in grid index order (x fastest, then y, then z), each
//                 `words per probe` u16 words in the sh module's packed form; the last word of
//                 each probe is its meta word: bits 0-2 its ProbeFlag bits (per-probe flags),
//                 bit 3 its form, bits 4-15 its shared exponents.
//        -     4  u32 moment map resolution R (0: no distance moments; 1..16)   [version 2]
//        -     -  probes × R² u32 moment texels in grid index order, moment_map.h's octahedral
//                 texel order, each half(mean d) | half(mean d²) << 16 over the volume's moment
//                 range (ProbeVolume::moment_range)                               [version 2]
//        -     -  probes × 3 f32 relocation offsets, metres from the grid position (each axis
//                 clamped to ProbeVolume's kMaxRelocation cells when read)        [version 2]
// A version 1 file is exactly 64 + probes × words × 2 bytes, a version 2 file
// 4 + probes × (R² × 4 + 12) more; readers reject anything else. Probe positions follow from counts and bounds
// (probe_grid.h: cell centres, inset half a cell).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "probes/probe_grid.h"
#include "probes/probe_volume.h"
#include "probes/volume_packing.h"

namespace ddish::probes {

inline constexpr char kVolumeMagic[4] = {'D', 'D', 'P', 'V'};
inline constexpr std::uint32_t kVolumeVersion = 2;
inline constexpr std::size_t kVolumeHeaderBytes = 64;

struct VolumeFile {
  ProbeGrid grid;
  std::uint64_t frame = 0;  // updates received
  PackedVolume packed;
  int moment_resolution = 0;            // 0: no moments (every version 1 file)
  std::vector<std::uint32_t> moments;   // probes × R² packed texels
  std::vector<float> offsets;           // probes × 3 (version 2); empty: none

  // The probe volume it holds: unpacked coefficients, flags, moments and offsets. Per-probe update counts are
  // not stored, so the volume's first update after loading replaces a probe's average
  // (weight 1/1) unless the caller sets ProbeState::updates.
  ProbeVolume to_volume() const;
};

// Writes the volume's packed form to `path` and its summary to `path` + ".json", each whole or
// not at all (io/atomic_file.h). Throws std::runtime_error naming the file when it cannot be
// written.
void write_volume_file(const std::string& path, const ProbeVolume& volume,
                       const PackedVolume& packed);

// Reads and validates a volume file. Throws std::runtime_error naming the file and the
// problem (not a DDPV file, unsupported version, inconsistent sizes, truncated).
VolumeFile read_volume_file(const std::string& path);

}  // namespace ddish::probes
