// Importance sampling of an equirectangular environment map (scene/environment_map.h) for
// next-event estimation. A piecewise-constant 2D distribution over the map's texels: texel (i, j)
// is picked with probability proportional to its luminance times sin(theta) at its row's centre
// (the solid angle a texel row covers), first its row from the marginal, then its column from
// the row's conditional; the point is uniform in (u, v) within the texel. The density per solid
// angle is p(u, v) / (2 pi^2 sin(theta)), with theta the sampled direction's polar angle (the
// Jacobian of (u, v) -> direction: d omega = 2 pi^2 sin(theta) du dv). The tracer combines it with
// BSDF sampling by the power heuristic, as it does for emissive triangles (trace/tracer.cpp).
#pragma once

#include <cstddef>
#include <memory>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace ddish::scene {
struct EnvironmentMap;
}

namespace ddish::trace {

struct EnvironmentSample {
  glm::vec3 wi{0.0f};        // unit world direction toward the environment
  glm::vec3 radiance{0.0f};  // the map's (bilinear) radiance from wi
  float pdf = 0.0f;          // per unit solid angle
};

// The sampling tables, read-only (trace_vk mirrors them on the GPU instead of building its own):
// per texel (row-major, row 0 at the top) its weight, luminance x sin(theta) at its row's
// centre; the normalised CDF over rows (height + 1 entries, from 0 to 1); each row's normalised
// CDF over its columns (height rows of width + 1 entries); and the weights' total (0: a black
// map, nothing to sample). sample() picks with the CDFs; the density of a texel in (u, v) is
// weight x width x height / total.
struct EnvironmentTables {
  int width = 0;
  int height = 0;
  std::span<const double> weights;
  std::span<const double> row_cdf;
  std::span<const double> column_cdf;
  double total = 0.0;
};

class EnvironmentLight {
 public:
  explicit EnvironmentLight(std::shared_ptr<const scene::EnvironmentMap> map);

  // False when the map is black (nothing to sample) or u lands on a pole (sin(theta) = 0).
  bool sample(const glm::vec2& u, EnvironmentSample& out) const;
  // The density with which sample() returns the unit direction wi, per solid angle.
  float pdf(const glm::vec3& wi) const;
  glm::vec3 radiance(const glm::vec3& wi) const;
  bool empty() const { return total_ <= 0.0; }

  // The probability that sample() picks texel (x, y) (for tests).
  double texel_probability(int x, int y) const;

  const scene::EnvironmentMap& map() const { return *map_; }
  EnvironmentTables tables() const { return {width_, height_, weights_, row_cdf_, col_cdf_, total_}; }

 private:
  std::shared_ptr<const scene::EnvironmentMap> map_;
  int width_ = 0;
  int height_ = 0;
  std::vector<double> weights_;   // per texel, luminance * sin(theta_row)
  std::vector<double> row_cdf_;   // height + 1 entries, normalised
  std::vector<double> col_cdf_;   // height rows of width + 1 entries, each normalised
  std::vector<double> row_sums_;  // per row
  double total_ = 0.0;
};

}  // namespace ddish::trace
