#include "probes/surface_cells.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "scene/scene.h"

namespace ddish::probes {

namespace {

// Interpolation cells per axis: between neighbouring probes, one cell where an axis has a
// single probe (that probe then covers the axis alone).
glm::ivec3 cell_counts(const ProbeGrid& grid) { return glm::max(grid.counts() - 1, glm::ivec3(1)); }

class CellMarks {
 public:
  explicit CellMarks(const ProbeGrid& grid)
      : grid_(grid), cells_(cell_counts(grid)), marked_(std::size_t(cells_.x) * cells_.y * cells_.z, 0) {}

  // Marks the cells a world-space triangle overlaps, each grown by the margin.
  void triangle(const glm::vec3& wa, const glm::vec3& wb, const glm::vec3& wc) {
    const glm::vec3 a = grid_.grid_coordinate(wa), b = grid_.grid_coordinate(wb),
                    c = grid_.grid_coordinate(wc);
    if (!finite(a) || !finite(b) || !finite(c)) return;
    const glm::vec3 lo = glm::min(a, glm::min(b, c)), hi = glm::max(a, glm::max(b, c));
    const glm::vec3 last = glm::vec3(grid_.counts() - 1);
    const bool inside = glm::all(glm::greaterThanEqual(lo, glm::vec3(0.0f))) &&
                        glm::all(glm::lessThanEqual(hi, last));
    const auto [c0, c1] = cell_range(lo, hi);
    for (int z = c0.z; z <= c1.z; ++z)
      for (int y = c0.y; y <= c1.y; ++y)
        for (int x = c0.x; x <= c1.x; ++x) {
          const glm::vec3 cell(x, y, z);
          // A triangle that leaves the grid is clamped onto its border cells by the shader: its
          // whole clamped box counts (conservative), without the exact test.
          if (!inside || triangle_overlaps_box(a, b, c, cell - kSurfaceMarginCells,
                                               cell + 1.0f + kSurfaceMarginCells))
            marked_[index(x, y, z)] = 1;
        }
  }

  // Marks every cell a world-space box overlaps (grown by the margin, clamped to the grid).
  void box(const scene::Aabb& world) {
    if (world.empty()) return;
    const glm::vec3 lo = grid_.grid_coordinate(world.min), hi = grid_.grid_coordinate(world.max);
    if (!finite(lo) || !finite(hi)) return;
    const auto [c0, c1] = cell_range(glm::min(lo, hi), glm::max(lo, hi));
    for (int z = c0.z; z <= c1.z; ++z)
      for (int y = c0.y; y <= c1.y; ++y)
        for (int x = c0.x; x <= c1.x; ++x) marked_[index(x, y, z)] = 1;
  }

  // A probe is needed when one of the cells it is a corner of is marked.
  std::vector<bool> probes() const {
    std::vector<bool> needed(grid_.probe_count(), false);
    for (std::uint32_t i = 0; i < grid_.probe_count(); ++i) {
      const glm::ivec3 p = grid_.cell(i);
      const glm::ivec3 lo = glm::clamp(p - 1, glm::ivec3(0), cells_ - 1);
      const glm::ivec3 hi = glm::clamp(p, glm::ivec3(0), cells_ - 1);
      for (int z = lo.z; z <= hi.z && !needed[i]; ++z)
        for (int y = lo.y; y <= hi.y && !needed[i]; ++y)
          for (int x = lo.x; x <= hi.x && !needed[i]; ++x) needed[i] = marked_[index(x, y, z)] != 0;
    }
    return needed;
  }

 private:
  static bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

  // The first and last cell whose box, grown by the margin, reaches the grid-coordinate range
  // [lo, hi]: cell c spans [c - m, c + 1 + m]. Clamped to the grid's cells.
  std::pair<glm::ivec3, glm::ivec3> cell_range(const glm::vec3& lo, const glm::vec3& hi) const {
    const auto clamped = [&](const glm::vec3& f) {
      return glm::clamp(glm::ivec3(glm::clamp(f, glm::vec3(-1.0f), glm::vec3(cells_))), glm::ivec3(0), cells_ - 1);
    };
    return {clamped(glm::ceil(lo - 1.0f - kSurfaceMarginCells)), clamped(glm::floor(hi + kSurfaceMarginCells))};
  }
  std::size_t index(int x, int y, int z) const {
    return std::size_t(x) + std::size_t(cells_.x) * (std::size_t(y) + std::size_t(cells_.y) * std::size_t(z));
  }

  const ProbeGrid& grid_;
  glm::ivec3 cells_;
  std::vector<std::uint8_t> marked_;
};

void mark_instance_triangles(CellMarks& marks, const scene::Scene& s, const scene::Instance& inst) {
  const scene::Mesh& m = s.meshes[std::size_t(inst.mesh)];
  const auto world = [&](std::uint32_t i) { return glm::vec3(inst.transform * glm::vec4(m.positions[i], 1.0f)); };
  for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
    const std::uint32_t i0 = m.indices[t], i1 = m.indices[t + 1], i2 = m.indices[t + 2];
    if (i0 >= m.positions.size() || i1 >= m.positions.size() || i2 >= m.positions.size()) continue;
    marks.triangle(world(i0), world(i1), world(i2));
  }
}

scene::Aabb instance_bounds(const scene::Scene& s, const scene::Instance& inst) {
  return s.meshes[std::size_t(inst.mesh)].bounds.transformed(inst.transform);
}

bool same(const scene::Aabb& a, const scene::Aabb& b) { return a.min == b.min && a.max == b.max; }

// Projects v onto axis and returns the interval of the three points.
void project(const glm::vec3& axis, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, float& lo, float& hi) {
  const float pa = glm::dot(axis, a), pb = glm::dot(axis, b), pc = glm::dot(axis, c);
  lo = std::min({pa, pb, pc});
  hi = std::max({pa, pb, pc});
}

}  // namespace

bool triangle_overlaps_box(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
                           const glm::vec3& lo, const glm::vec3& hi) {
  // In the box's frame: centred at the origin, half extents h.
  const glm::vec3 centre = 0.5f * (lo + hi), h = 0.5f * (hi - lo);
  const glm::vec3 v0 = a - centre, v1 = b - centre, v2 = c - centre;
  // The box's own axes.
  for (int k = 0; k < 3; ++k) {
    if (std::min({v0[k], v1[k], v2[k]}) > h[k] || std::max({v0[k], v1[k], v2[k]}) < -h[k]) return false;
  }
  // An axis separates when the triangle's interval misses the box's, whose radius on that axis
  // is the sum of |axis_k| h_k.
  const auto separates = [&](const glm::vec3& axis) {
    float t0, t1;
    project(axis, v0, v1, v2, t0, t1);
    const float r = glm::dot(glm::abs(axis), h);
    return t0 > r || t1 < -r;
  };
  const glm::vec3 e[3] = {v1 - v0, v2 - v1, v0 - v2};
  if (separates(glm::cross(e[0], e[1]))) return false;  // the triangle's plane
  for (const glm::vec3& edge : e)
    for (int k = 0; k < 3; ++k) {
      glm::vec3 unit(0.0f);
      unit[k] = 1.0f;
      if (separates(glm::cross(edge, unit))) return false;
    }
  return true;
}

std::vector<bool> probes_near_surfaces(const ProbeGrid& grid, scene::Scene& s) {
  CellMarks marks(grid);
  std::vector<bool> moving(s.instances.size(), false);
  if (!s.animations.empty()) {
    // The bounds of every instance at kAnimationSamples + 1 times over the animation: an
    // instance whose bounds differ anywhere moves, and marks what each step between two samples
    // sweeps (the union of their boxes).
    const double t_now = s.time, duration = s.animation_duration();
    std::vector<std::vector<scene::Aabb>> boxes(s.instances.size());
    for (int k = 0; k <= kAnimationSamples; ++k) {
      s.pose(duration * double(k) / double(kAnimationSamples));
      for (std::size_t i = 0; i < s.instances.size(); ++i) boxes[i].push_back(instance_bounds(s, s.instances[i]));
    }
    s.pose(t_now);
    for (std::size_t i = 0; i < s.instances.size(); ++i) {
      for (std::size_t k = 1; k < boxes[i].size(); ++k) moving[i] = moving[i] || !same(boxes[i][k], boxes[i][0]);
      if (!moving[i]) continue;
      for (std::size_t k = 1; k < boxes[i].size(); ++k) {
        scene::Aabb step = boxes[i][k - 1];
        step.expand(boxes[i][k]);
        marks.box(step);
      }
    }
  }
  for (std::size_t i = 0; i < s.instances.size(); ++i)
    if (!moving[i]) mark_instance_triangles(marks, s, s.instances[i]);
  return marks.probes();
}

std::uint32_t leave_out_probes(ProbeVolume& volume, const std::vector<bool>& near_surface) {
  std::uint32_t left_out = 0;
  for (std::uint32_t i = 0; i < volume.probe_count() && i < near_surface.size(); ++i) {
    if (near_surface[i] || !volume.state(i).active()) continue;
    volume.deactivate(i, false);
    ++left_out;
  }
  return left_out;
}

}  // namespace ddish::probes
