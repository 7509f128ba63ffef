// The layout of a probe volume: a regular grid of counts.x × counts.y × counts.z probes over an
// axis-aligned box. Probe (x, y, z) sits at the centre of cell (x, y, z) when the box is divided
// into counts cells per axis, i.e. inset by half a cell from the bounds. Scene bounds usually
// coincide with walls, floors and ceilings; probes placed on the bounds would sit exactly on those
// surfaces (half their rays grazing or hitting the back of the wall), whereas inset probes lie in
// the open space every surface point is interpolated from, at most half a cell from any point of
// the box along each axis.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

#include "scene/aabb.h"

namespace ddish::probes {

class ProbeGrid {
 public:
  // Largest volume ProbeGrid accepts: more probes than a server could ever update per frame is
  // a mistaken spacing, not a request.
  static constexpr std::int64_t kMaxProbes = 1 << 24;

  ProbeGrid() = default;  // one probe at the origin
  // counts >= 1 on every axis; bounds non-empty (a zero extent on an axis is allowed).
  // Throws std::invalid_argument otherwise.
  ProbeGrid(const scene::Aabb& bounds, const glm::ivec3& counts);

  // The grid over bounds whose probe spacing is at most `spacing` metres on every axis (the
  // fewest probes that do so). Throws std::invalid_argument for spacing <= 0 or too many probes.
  static ProbeGrid fit_spacing(const scene::Aabb& bounds, float spacing);

  // Automatic placement when nothing is asked for: the spacing that puts kAutoLongestAxisProbes
  // probes along the longest axis of the bounds (at most 16^3 = 4096 probes). DDISH-GI's room-size
  // scenes use 16 along the longest axis (Sponza 16x8x8): about one probe per metre indoors, and
  // an update of ~1000 probes x 256 rays in tens of milliseconds on the CPU.
  static constexpr int kAutoLongestAxisProbes = 16;
  static ProbeGrid fit_auto(const scene::Aabb& bounds);

  // The automatic grid around what the bounds hold, for bounds that are the scene's own (an
  // object in open space, not a room's walls): fit_auto over the bounds grown on every side by
  // kAutoMarginCells cells of the resulting grid, i.e. by longest extent / 14. The outermost
  // probes then lie half a cell outside the bounds, so an object that fills its bounds (a box, a
  // sphere) has a layer of probes in the open around it; since inactive probes (inside
  // geometry) are weighted out of the interpolation, every point of its surface reads probes
  // that see it from outside. Without the margin every probe of a box lies inside it, and the
  // box renders black. A point gets one probe on it, as with fit_auto.
  static constexpr int kAutoMarginCells = 1;
  static ProbeGrid fit_auto_around(const scene::Aabb& bounds);

  const scene::Aabb& bounds() const { return bounds_; }
  const glm::ivec3& counts() const { return counts_; }
  // Distance between neighbouring probes per axis (the cell size); 0 on an axis of zero extent.
  const glm::vec3& spacing() const { return spacing_; }
  // The smallest non-zero cell size over the axes (0 when every axis is flat: a single point).
  float smallest_spacing() const;
  std::uint32_t probe_count() const {
    return std::uint32_t(counts_.x) * std::uint32_t(counts_.y) * std::uint32_t(counts_.z);
  }

  // Linear index: x fastest, then y, then z (the order of packed probes on disk and on the GPU).
  std::uint32_t index(const glm::ivec3& cell) const {
    return std::uint32_t(cell.x + counts_.x * (cell.y + counts_.y * cell.z));
  }
  glm::ivec3 cell(std::uint32_t index) const {
    auto cx = std::uint32_t(counts_.x), cy = std::uint32_t(counts_.y);
    return {int(index % cx), int((index / cx) % cy), int(index / (cx * cy))};
  }
  bool contains(const glm::ivec3& cell) const {
    return glm::all(glm::greaterThanEqual(cell, glm::ivec3(0))) &&
           glm::all(glm::lessThan(cell, counts_));
  }

  // World position of probe (x, y, z).
  glm::vec3 position(const glm::ivec3& cell) const { return origin_ + glm::vec3(cell) * spacing_; }
  glm::vec3 position(std::uint32_t index) const { return position(cell(index)); }

  // Continuous grid coordinate of a world point: probe (x, y, z) is at exactly (x, y, z), so
  // floor() gives the lower corner probe of the interpolation cell and fract() the weights.
  // Axes of zero extent map to 0.
  glm::vec3 grid_coordinate(const glm::vec3& world) const;

  bool operator==(const ProbeGrid& other) const {
    return counts_ == other.counts_ && bounds_.min == other.bounds_.min &&
           bounds_.max == other.bounds_.max;
  }

 private:
  scene::Aabb bounds_{glm::vec3(0.0f), glm::vec3(0.0f)};
  glm::ivec3 counts_{1};
  glm::vec3 spacing_{0.0f};
  glm::vec3 origin_{0.0f};  // position of probe (0, 0, 0)
};

}  // namespace ddish::probes
