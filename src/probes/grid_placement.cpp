#include "probes/grid_placement.h"

#include <algorithm>
#include <cmath>
#include <random>

#include <tbb/parallel_for.h>

#include "scene/scene.h"
#include "trace/embree_scene.h"
#include "trace/frame.h"
#include "trace/sampling.h"
#include "trace/tracer.h"

namespace ddish::probes {

namespace {

// Uniform in [0, 1) from 24 bits of the generator: the same numbers from every standard
// library, unlike std::uniform_real_distribution.
float unit(std::mt19937_64& rng) { return float(rng() >> 40) * (1.0f / 16777216.0f); }

struct WorldTriangle {
  glm::vec3 a, b, c;
  bool double_sided;
};

// Points scored per parallel task; the per-task sums are added in task order.
constexpr std::size_t kChunk = 512;

}  // namespace

std::vector<SurfaceSample> sample_surfaces(const scene::Scene& s, std::uint32_t count,
                                           std::uint64_t seed) {
  std::vector<WorldTriangle> triangles;
  std::vector<double> cumulative;  // running sum of the areas
  double total = 0.0;
  for (const scene::Instance& inst : s.instances) {
    if (inst.mesh < 0 || std::size_t(inst.mesh) >= s.meshes.size()) continue;
    const scene::Mesh& m = s.meshes[std::size_t(inst.mesh)];
    const bool two_sided = s.material_of(m).double_sided;
    const auto world = [&](std::uint32_t i) { return glm::vec3(inst.transform * glm::vec4(m.positions[i], 1.0f)); };
    for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
      const std::uint32_t i0 = m.indices[t], i1 = m.indices[t + 1], i2 = m.indices[t + 2];
      if (i0 >= m.positions.size() || i1 >= m.positions.size() || i2 >= m.positions.size()) continue;
      WorldTriangle w{world(i0), world(i1), world(i2), two_sided};
      const double area = 0.5 * double(glm::length(glm::cross(w.b - w.a, w.c - w.a)));
      if (!(area > 0.0) || !std::isfinite(area)) continue;
      total += area;
      triangles.push_back(w);
      cumulative.push_back(total);
    }
  }
  std::vector<SurfaceSample> points;
  if (triangles.empty() || count == 0) return points;
  std::mt19937_64 rng(seed);
  points.reserve(count);
  for (std::uint32_t k = 0; k < count; ++k) {
    const double pick = double(unit(rng)) * total;
    const std::size_t t = std::min<std::size_t>(
        std::size_t(std::upper_bound(cumulative.begin(), cumulative.end(), pick) - cumulative.begin()),
        triangles.size() - 1);
    const WorldTriangle& w = triangles[t];
    // Uniform on the triangle: fold the unit square's upper half onto the lower.
    float u = unit(rng), v = unit(rng);
    if (u + v > 1.0f) {
      u = 1.0f - u;
      v = 1.0f - v;
    }
    SurfaceSample p;
    p.position = w.a + u * (w.b - w.a) + v * (w.c - w.a);
    p.normal = glm::normalize(glm::cross(w.b - w.a, w.c - w.a));
    if (w.double_sided && (k & 1u)) p.normal = -p.normal;
    points.push_back(p);
  }
  return points;
}

double visible_weight(const ProbeGrid& grid, std::span<const SurfaceSample> points,
                      const SegmentVisible& visible) {
  if (points.empty()) return 0.0;
  const float lift = kPlacementLiftCells * grid.smallest_spacing();
  const glm::ivec3 last = grid.counts() - 1;
  const std::size_t chunks = (points.size() + kChunk - 1) / kChunk;
  std::vector<double> sums(chunks, 0.0);
  tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t c) {
    double sum = 0.0;
    const std::size_t end = std::min(points.size(), (c + 1) * kChunk);
    for (std::size_t k = c * kChunk; k < end; ++k) {
      const SurfaceSample& p = points[k];
      const glm::vec3 g = glm::clamp(grid.grid_coordinate(p.position), glm::vec3(0.0f), glm::vec3(last));
      const glm::ivec3 base = glm::clamp(glm::ivec3(glm::floor(g)), glm::ivec3(0), glm::max(last - 1, glm::ivec3(0)));
      const glm::vec3 t = glm::clamp(g - glm::vec3(base), 0.0f, 1.0f);
      const glm::vec3 from = p.position + lift * p.normal;
      for (int corner = 0; corner < 8; ++corner) {
        const glm::ivec3 o(corner & 1, (corner >> 1) & 1, corner >> 2);
        const glm::vec3 w3 = glm::mix(1.0f - t, t, glm::vec3(o));
        const float w = w3.x * w3.y * w3.z;
        if (!(w > 0.0f)) continue;
        const glm::ivec3 probe = glm::min(base + o, last);
        if (visible(from, grid.position(probe))) sum += double(w);
      }
    }
    sums[c] = sum;
  });
  double total = 0.0;
  for (double s : sums) total += s;
  return total / double(points.size());
}

ProbeGrid shifted_grid(const ProbeGrid& grid, const glm::vec3& offset_cells) {
  scene::Aabb moved = grid.bounds();
  const glm::vec3 d = offset_cells * grid.spacing();
  moved.min += d;
  moved.max += d;
  return ProbeGrid(moved, grid.counts());
}

GridFit fit_grid_placement(const ProbeGrid& grid, std::span<const SurfaceSample> points,
                           const SegmentVisible& visible) {
  GridFit fit;
  fit.grid = grid;
  fit.points = std::uint32_t(points.size());
  if (points.empty()) return fit;
  fit.unmoved_score = fit.score = visible_weight(grid, points, visible);
  fit.grids_scored = 1;
  for (int axis = 0; axis < 3; ++axis) {
    if (!(grid.spacing()[axis] > 0.0f)) continue;  // a flat axis has nowhere to move
    glm::vec3 best_offset = fit.offset_cells;
    double best = fit.score;
    for (float o : kPlacementOffsets) {
      if (o == fit.offset_cells[axis]) continue;
      glm::vec3 offset = fit.offset_cells;
      offset[axis] = o;
      const ProbeGrid candidate = shifted_grid(grid, offset);
      const double score = visible_weight(candidate, points, visible);
      ++fit.grids_scored;
      if (score > best) {
        best = score;
        best_offset = offset;
      }
    }
    if (best >= fit.score + kPlacementMinGain) {
      fit.score = best;
      fit.offset_cells = best_offset;
      fit.grid = shifted_grid(grid, best_offset);
    }
  }
  return fit;
}

std::vector<SurfaceSample> lit_surfaces(std::span<const SurfaceSample> points, const trace::Tracer& tracer,
                                        float lift, std::uint32_t paths) {
  std::vector<std::uint8_t> lit(points.size(), 0);
  tbb::parallel_for(std::size_t(0), points.size(), [&](std::size_t k) {
    const SurfaceSample& p = points[k];
    const trace::Frame frame = trace::Frame::from_normal(p.normal);
    trace::Sampler sampler(kPlacementSeed, k);
    for (std::uint32_t i = 0; i < paths && !lit[k]; ++i) {
      trace::Ray ray;
      ray.origin = p.position + lift * p.normal;
      ray.direction = frame.to_world(trace::sample_cosine_hemisphere(sampler.next2d()));
      const glm::vec3 L = tracer.trace_path(ray, sampler).radiance;
      lit[k] = L.x + L.y + L.z > 0.0f;
    }
  });
  std::vector<SurfaceSample> kept;
  for (std::size_t k = 0; k < points.size(); ++k)
    if (lit[k]) kept.push_back(points[k]);
  return kept;
}

std::vector<SurfaceSample> camera_surfaces(const scene::Scene& s, const trace::EmbreeScene& embree,
                                           std::uint32_t count, std::uint64_t seed) {
  std::vector<SurfaceSample> points;
  if (s.cameras.empty()) return points;
  std::mt19937_64 rng(seed);
  for (std::uint32_t k = 0; k < count; ++k) {
    const scene::Camera& c = s.cameras[k % s.cameras.size()];
    const float tan_y = std::tan(0.5f * c.yfov), tan_x = tan_y * c.aspect.value_or(4.0f / 3.0f);
    const glm::vec3 f = glm::normalize(c.forward);
    glm::vec3 right = glm::cross(f, c.up);
    if (!(glm::dot(right, right) > 1e-12f))  // an up along the view: any frame will do
      right = glm::cross(f, std::abs(f.y) < 0.9f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(1.0f, 0.0f, 0.0f));
    right = glm::normalize(right);
    const glm::vec3 up = glm::cross(right, f);
    const float u = 2.0f * unit(rng) - 1.0f, v = 2.0f * unit(rng) - 1.0f;
    trace::Ray ray;
    ray.origin = c.eye;
    ray.direction = glm::normalize(f + u * tan_x * right + v * tan_y * up);
    trace::Hit hit;
    if (!embree.intersect(ray, trace::RayQuery{}, hit)) continue;
    const scene::Instance& inst = s.instances[std::size_t(hit.instance)];
    const scene::Mesh& m = s.meshes[std::size_t(inst.mesh)];
    const std::size_t t = std::size_t(hit.prim) * 3;
    if (t + 2 >= m.indices.size()) continue;
    const auto world = [&](std::size_t i) { return glm::vec3(inst.transform * glm::vec4(m.positions[m.indices[i]], 1.0f)); };
    glm::vec3 n = glm::cross(world(t + 1) - world(t), world(t + 2) - world(t));
    if (!(glm::dot(n, n) > 0.0f)) continue;
    n = glm::normalize(n);
    if (glm::dot(n, ray.direction) > 0.0f) n = -n;  // the side the camera sees
    points.push_back({ray.origin + hit.t * ray.direction, n});
  }
  return points;
}

GridFit fit_grid_placement(const ProbeGrid& grid, const scene::Scene& s, const trace::Tracer& tracer) {
  const trace::EmbreeScene& embree = tracer.embree_scene();
  std::vector<SurfaceSample> points = camera_surfaces(s, embree, kPlacementSurfacePoints, kPlacementSeed);
  if (points.empty())
    points = lit_surfaces(sample_surfaces(s, kPlacementSurfacePoints, kPlacementSeed), tracer,
                          kPlacementLiftCells * grid.smallest_spacing(), kPlacementLightPaths);
  const SegmentVisible visible = [&embree](const glm::vec3& from, const glm::vec3& to) {
    const glm::vec3 d = to - from;
    const float length = glm::length(d);
    if (!(length > 0.0f)) return true;
    return !embree.occluded(from, d / length, 0.0f, length, trace::RayQuery{});
  };
  return fit_grid_placement(grid, points, visible);
}

}  // namespace ddish::probes
