// The CPU side of ProbeTextures' texel layout (probe_lighting.glsl describes it): a probe's
// slots (w, w c0.r, w c0.g, w c0.b, w c1.r, ...) as IEEE halves, four per RGBA16F texel, and
// dirty probes grouped into runs along grid rows, one buffer-to-image copy region each.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "probes/probe_volume.h"
#include "sh/basis.h"

namespace ddish::raster {

// Slots of a probe at SH order `order`: its weight, then three per coefficient.
constexpr int probe_slot_count(int order) { return 1 + 3 * sh::coeff_count(order); }
// RGBA textures that hold those slots: 4 at L1, 7 at L2, 13 at L3, 19 at L4.
constexpr int probe_texture_count(int order) { return (probe_slot_count(order) + 3) / 4; }

// Counts of what fp16 could not hold, found while packing.
struct SlotClamps {
  std::uint32_t overflowed = 0;  // |value| > 65504: written as +-65504
  std::uint32_t not_finite = 0;  // NaN written as 0, +-Inf as +-65504
};

// Writes the 4 * probe_texture_count(order) halves of probe `probe` into out (texture t's texel
// at out[4t .. 4t+3]): weight 1 for an active probe and 0 for an inactive one, coefficients
// premultiplied by it, bands above the volume's order zero, bands above `order` dropped, unused
// slots zero. Never writes Inf or NaN.
void pack_probe_slots(const probes::ProbeVolume& volume, std::uint32_t probe, int order,
                      std::span<std::uint16_t> out, SlotClamps& clamps);

// Writes probe `probe`'s visibility record for the GPU (volume.moment_texels() + 3 uints): each
// moment texel as half(mean d) | half(mean d^2) << 16, then its relocation offset as 3 floats.
void pack_probe_moments(const probes::ProbeVolume& volume, std::uint32_t probe,
                        std::span<std::uint32_t> out, SlotClamps& clamps);

// Consecutive probes of one grid row (same y and z, x increasing): probes first .. first+count-1
// in grid index order.
struct ProbeRun {
  std::uint32_t first = 0;
  std::uint32_t count = 0;
};

// The probes sorted, without repeats, cut into row runs. Throws std::out_of_range for an index
// past probe_count.
std::vector<ProbeRun> probe_row_runs(std::span<const std::uint32_t> probes,
                                     const glm::ivec3& counts);

}  // namespace ddish::raster
