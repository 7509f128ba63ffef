#include "raster/clusters.h"

#include <algorithm>
#include <limits>

#include <meshoptimizer.h>

#include "scene/scene.h"

namespace ddish::raster {

ClusteredIndices cluster_mesh(const scene::Mesh& mesh, std::uint32_t base_index) {
  ClusteredIndices out;
  const std::size_t index_count = mesh.indices.size() - mesh.indices.size() % 3;
  if (index_count == 0 || mesh.positions.empty()) return out;
  const auto* positions = &mesh.positions[0].x;
  const std::size_t vertex_count = mesh.positions.size();
  constexpr std::size_t stride = sizeof(glm::vec3);

  // Spatial order first, so that a chunk of consecutive triangles is a compact piece of the
  // surface (small bounds, a narrow normal cone); the vertex-cache order is then found within
  // each chunk, which keeps the chunk's triangle set unchanged.
  std::vector<std::uint32_t> sorted(index_count);
  meshopt_spatialSortTriangles(sorted.data(), mesh.indices.data(), index_count, positions,
                               vertex_count, stride);
  out.indices.resize(index_count);
  const std::size_t chunk = std::size_t{kClusterTriangles} * 3;
  for (std::size_t first = 0; first < index_count; first += chunk) {
    const std::size_t count = std::min(chunk, index_count - first);
    std::uint32_t* dst = out.indices.data() + first;
    meshopt_optimizeVertexCache(dst, sorted.data() + first, count, vertex_count);

    Cluster c;
    c.first_index = base_index + static_cast<std::uint32_t>(first);
    c.index_count = static_cast<std::uint32_t>(count);
    c.min = glm::vec3(std::numeric_limits<float>::infinity());
    c.max = -c.min;
    for (std::size_t i = 0; i < count; ++i) {
      const glm::vec3& p = mesh.positions[dst[i]];
      c.min = glm::min(c.min, p);
      c.max = glm::max(c.max, p);
    }
    const meshopt_Bounds b = meshopt_computeClusterBounds(dst, count, positions, vertex_count, stride);
    c.cone_apex = {b.cone_apex[0], b.cone_apex[1], b.cone_apex[2]};
    c.cone_axis = {b.cone_axis[0], b.cone_axis[1], b.cone_axis[2]};
    c.cone_cutoff = b.cone_cutoff;
    out.clusters.push_back(c);
  }
  return out;
}

bool cone_backfacing(const Cluster& c, const glm::vec3& eye) {
  if (c.cone_cutoff >= 1.0f) return false;
  const glm::vec3 d = c.cone_apex - eye;
  const float len = glm::length(d);
  // An eye on the apex sees the triangles edge-on at best; keep them rather than divide by 0.
  if (len <= 0.0f) return false;
  return glm::dot(d, c.cone_axis) >= c.cone_cutoff * len;
}

}  // namespace ddish::raster
