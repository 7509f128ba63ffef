#include "raster/probe_slots.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <stdexcept>
#include <string>

#include "sh/packing.h"

namespace ddish::raster {

namespace {

// fp16 of v with out-of-range values saturated and NaN zeroed, counted: a texture that held
// Inf would turn every interpolation touching the probe into Inf or NaN.
std::uint16_t to_half(float v, SlotClamps& clamps) {
  if (std::isnan(v)) {
    ++clamps.not_finite;
    return sh::float_to_half(0.0f);
  }
  if (std::isinf(v)) {
    ++clamps.not_finite;
    return sh::float_to_half(std::copysign(sh::kHalfMax, v));
  }
  if (std::abs(v) > sh::kHalfMax) {
    ++clamps.overflowed;
    return sh::float_to_half(std::copysign(sh::kHalfMax, v));
  }
  return sh::float_to_half(v);
}

}  // namespace

void pack_probe_slots(const probes::ProbeVolume& volume, std::uint32_t probe, int order,
                      std::span<std::uint16_t> out, SlotClamps& clamps) {
  const std::size_t texel_slots = 4 * std::size_t(probe_texture_count(order));
  if (out.size() < texel_slots)
    throw std::invalid_argument("probe slot buffer of " + std::to_string(out.size()) +
                                " halves, " + std::to_string(texel_slots) + " needed");
  std::fill(out.begin(), out.begin() + std::ptrdiff_t(texel_slots), std::uint16_t{0});
  const bool active = volume.state(probe).active();
  out[0] = sh::float_to_half(active ? 1.0f : 0.0f);
  if (!active) return;  // deactivate() zeroes the coefficients too; w = 0 weights it out
  const auto coeffs = volume.coefficients(probe);
  const int n = std::min(sh::coeff_count(order), volume.coefficient_count());
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c)
      out[std::size_t(1 + 3 * i + c)] = to_half(coeffs[std::size_t(i)][c], clamps);
}

void pack_probe_moments(const probes::ProbeVolume& volume, std::uint32_t probe,
                        std::span<std::uint32_t> out, SlotClamps& clamps) {
  const auto moments = volume.moments(probe);
  if (out.size() != moments.size() + 3)
    throw std::invalid_argument("probe visibility record of " + std::to_string(out.size()) +
                                " uints, " + std::to_string(moments.size() + 3) + " needed");
  for (std::size_t t = 0; t < moments.size(); ++t)
    out[t] = std::uint32_t(to_half(moments[t].x, clamps)) |
             (std::uint32_t(to_half(moments[t].y, clamps)) << 16);
  const glm::vec3 offset = volume.offset(probe);
  for (int a = 0; a < 3; ++a) out[moments.size() + std::size_t(a)] = std::bit_cast<std::uint32_t>(offset[a]);
}

std::vector<ProbeRun> probe_row_runs(std::span<const std::uint32_t> probes,
                                     const glm::ivec3& counts) {
  const std::uint32_t total = std::uint32_t(counts.x) * std::uint32_t(counts.y) *
                              std::uint32_t(counts.z);
  std::vector<std::uint32_t> sorted(probes.begin(), probes.end());
  std::sort(sorted.begin(), sorted.end());
  sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
  if (!sorted.empty() && sorted.back() >= total)
    throw std::out_of_range("dirty probe " + std::to_string(sorted.back()) + " of a volume of " +
                            std::to_string(total) + " probes");
  std::vector<ProbeRun> runs;
  const auto row_length = std::uint32_t(counts.x);
  for (std::uint32_t p : sorted) {
    // A run continues while the next index is adjacent and still in the same row.
    if (!runs.empty() && runs.back().first + runs.back().count == p && p % row_length != 0)
      ++runs.back().count;
    else
      runs.push_back({p, 1});
  }
  return runs;
}

}  // namespace ddish::raster
