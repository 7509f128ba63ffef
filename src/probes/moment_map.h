// Per-probe distance moments for visibility-aware interpolation: for each direction, the mean
// first-hit distance and the mean squared distance of the probe's rays, kept as a small
// octahedral map (resolution R: R x R texels over the sphere) and read by the forward shader's
// Chebyshev test (shaders/include/probe_lighting.glsl). Distances are clamped to the volume's
// moment range (a miss counts as the range) and stored divided by it, so a texel holds
// (mean d / range, mean d^2 / range^2), both in [0, 1].
//
// The octahedral mapping (Cigolle et al., "A Survey of Efficient Representations for Independent
// Unit Vectors", 2014): dir / |dir|_1 projected onto the square; the lower hemisphere folded
// over the diagonals. shaders/include/octahedral.glsl's octahedral_texel is the same function.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace ddish::probes {

// The moment map resolutions ProbeVolume accepts: 0 (no moments) or 1..kMaxMomentResolution.
inline constexpr int kMaxMomentResolution = 16;

// Throws std::invalid_argument unless 0 <= resolution <= kMaxMomentResolution.
void check_moment_resolution(int resolution);

// The point of the square [-1, 1]^2 that unit vector `dir` maps to.
glm::vec2 octahedral_encode(const glm::vec3& dir);
// Texel (row-major, x fastest) of an R x R map that holds direction `dir`.
std::uint32_t moment_texel(const glm::vec3& dir, int resolution);

// One update's distances of one probe, binned per texel: sums of d and d^2 (already divided by
// the range) and the rays that fell into each texel.
struct MomentEstimate {
  explicit MomentEstimate(int resolution = 0);
  void clear();
  // A ray in direction `dir` (unit) whose first hit lay `distance` away, or that missed
  // (distance infinity); `range` is the volume's moment range.
  void add(const glm::vec3& dir, float distance, float range);

  int resolution = 0;
  std::vector<glm::vec2> sum;        // per texel: sum of d / range, sum of (d / range)^2
  std::vector<std::uint32_t> count;  // per texel: rays
};

}  // namespace ddish::probes
