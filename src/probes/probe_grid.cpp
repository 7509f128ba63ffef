#include "probes/probe_grid.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace ddish::probes {

namespace {

void check_bounds(const scene::Aabb& bounds) {
  if (bounds.empty())
    throw std::invalid_argument("probe volume bounds are empty");
  for (int a = 0; a < 3; ++a)
    if (!std::isfinite(bounds.min[a]) || !std::isfinite(bounds.max[a]))
      throw std::invalid_argument("probe volume bounds are not finite");
}

}  // namespace

ProbeGrid::ProbeGrid(const scene::Aabb& bounds, const glm::ivec3& counts)
    : bounds_(bounds), counts_(counts) {
  check_bounds(bounds);
  if (counts.x < 1 || counts.y < 1 || counts.z < 1)
    throw std::invalid_argument("probe grid counts must be at least 1 on every axis, got " +
                                std::to_string(counts.x) + "," + std::to_string(counts.y) + "," +
                                std::to_string(counts.z));
  // Each factor and the partial product are bounded before the next multiplication: counts
  // from a file may be near 2^31 each, and x y z would overflow even 64 bits (found by fuzzing).
  const std::int64_t xy = std::int64_t(counts.x) * counts.y;
  if (counts.x > kMaxProbes || counts.y > kMaxProbes || counts.z > kMaxProbes || xy > kMaxProbes ||
      xy * counts.z > kMaxProbes)
    throw std::invalid_argument("probe grid of " + std::to_string(counts.x) + "x" +
                                std::to_string(counts.y) + "x" + std::to_string(counts.z) +
                                " probes is larger than the limit of " +
                                std::to_string(kMaxProbes));
  spacing_ = bounds.extent() / glm::vec3(counts);
  origin_ = bounds.min + 0.5f * spacing_;
}

ProbeGrid ProbeGrid::fit_spacing(const scene::Aabb& bounds, float spacing) {
  if (!(spacing > 0.0f) || !std::isfinite(spacing))
    throw std::invalid_argument("probe spacing must be a positive number of metres, got " +
                                std::to_string(spacing));
  check_bounds(bounds);
  glm::ivec3 counts;
  std::int64_t total = 1;
  for (int a = 0; a < 3; ++a) {
    // ceil: the actual spacing extent / count never exceeds the one asked for.
    double n = std::ceil(double(bounds.extent()[a]) / double(spacing));
    if (n > double(kMaxProbes))
      throw std::invalid_argument("probe spacing " + std::to_string(spacing) +
                                  " m gives too many probes for the scene bounds");
    counts[a] = n < 1.0 ? 1 : int(n);
    total *= counts[a];  // <= 2^24 before, so <= 2^48 after: no overflow
    if (total > kMaxProbes) break;
  }
  if (total > kMaxProbes)
    throw std::invalid_argument("probe spacing " + std::to_string(spacing) + " m gives " +
                                std::to_string(total) + " probes, more than the limit of " +
                                std::to_string(kMaxProbes));
  return ProbeGrid(bounds, counts);
}

ProbeGrid ProbeGrid::fit_auto(const scene::Aabb& bounds) {
  check_bounds(bounds);
  glm::vec3 e = bounds.extent();
  float longest = std::max(e.x, std::max(e.y, e.z));
  if (longest <= 0.0f) return ProbeGrid(bounds, glm::ivec3(1));  // a point: one probe
  // A hair above longest / 16, so rounding in the division never makes it 17.
  return fit_spacing(bounds, longest / float(kAutoLongestAxisProbes) * (1.0f + 1e-6f));
}

ProbeGrid ProbeGrid::fit_auto_around(const scene::Aabb& bounds) {
  check_bounds(bounds);
  glm::vec3 e = bounds.extent();
  float longest = std::max(e.x, std::max(e.y, e.z));
  if (longest <= 0.0f) return ProbeGrid(bounds, glm::ivec3(1));
  // N cells along the grown longest axis, k of them margin on each side: m = k (L + 2m) / N.
  const float n = float(kAutoLongestAxisProbes), k = float(kAutoMarginCells);
  const float margin = k * longest / (n - 2.0f * k);
  scene::Aabb grown{bounds.min - glm::vec3(margin), bounds.max + glm::vec3(margin)};
  return fit_spacing(grown, margin / k * (1.0f + 1e-6f));
}

glm::vec3 ProbeGrid::grid_coordinate(const glm::vec3& world) const {
  glm::vec3 g(0.0f);
  for (int a = 0; a < 3; ++a)
    if (spacing_[a] > 0.0f) g[a] = (world[a] - origin_[a]) / spacing_[a];
  return g;
}

float ProbeGrid::smallest_spacing() const {
  float cell = 0.0f;
  for (int a = 0; a < 3; ++a)
    if (spacing_[a] > 0.0f) cell = cell > 0.0f ? std::min(cell, spacing_[a]) : spacing_[a];
  return cell;
}

}  // namespace ddish::probes
