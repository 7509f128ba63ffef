// The packed form of a probe volume, for the GPU, the wire and volume files: every probe is
// sh::packed_words(order) 16-bit words (56 bytes at L2) in grid index order, as the sh module's
// packer writes them: fp16 coefficients, or its shared-exponent form for a probe whose values
// fp16 cannot hold (next to a very bright emitter). Each probe's meta word carries its form
// (bit 3) and its ProbeFlag bits (bits 0-2: inactive, inside geometry, unclassified), so a shader
// reads form and weight from the probe itself.
//
// The encoding is chosen per probe rather than per volume: a volume with one bright emitter
// would otherwise give up fp16's relative precision in every dim probe (shared exponent keeps
// ~13 bits relative to a probe's largest value only). Probes never hold Inf or NaN when packed:
// a value beyond even the shared-exponent range (5.4e8) is saturated and reported.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "probes/probe_volume.h"
#include "sh/packing.h"

namespace ddish::probes {

enum class Encoding : std::uint32_t {
  kHalf = 0,       // every probe fp16
  kSharedExp = 1,  // every probe shared exponent
  kMixed = 2,      // per probe (meta word bit 3): fp16 where it fits
};

// What pack_volume may use: kAuto picks per probe (fp16 unless it would overflow); kHalf and
// kSharedExp force one form on every probe (a forced fp16 volume that overflows is saturated
// and reported as kOverflow, never written as Inf).
enum class EncodingPolicy { kAuto, kHalf, kSharedExp };

struct PackedVolume {
  int sh_order = 2;
  std::uint32_t words_per_probe = 0;  // sh::packed_words(sh_order)
  std::vector<std::uint16_t> words;   // probe_count * words_per_probe
  Encoding encoding = Encoding::kHalf;
  std::uint32_t half_probes = 0;        // probes in fp16 form
  std::uint32_t shared_exp_probes = 0;  // probes in shared-exponent form
  std::uint32_t overflowed_probes = 0;  // probes whose values were saturated (or NaN zeroed)
  sh::PackStatus status = sh::PackStatus::kOk;  // the worst status of any probe

  std::uint32_t probe_count() const {
    return words_per_probe ? std::uint32_t(words.size() / words_per_probe) : 0u;
  }
  std::span<const std::uint16_t> probe(std::uint32_t i) const {
    return {words.data() + std::size_t(i) * words_per_probe, words_per_probe};
  }
  std::size_t bytes() const { return words.size() * sizeof(std::uint16_t); }
};

PackedVolume pack_volume(const ProbeVolume& volume,
                         EncodingPolicy policy = EncodingPolicy::kAuto);

// The coefficients and flags of packed probe i (the inverse of pack_volume within the form's
// rounding).
sh::ShRgb unpack_probe(const PackedVolume& packed, std::uint32_t i);
std::uint8_t unpack_flags(const PackedVolume& packed, std::uint32_t i);

// "fp16", "shared-exponent" or "mixed".
std::string encoding_name(Encoding encoding);

}  // namespace ddish::probes
