// Mesh clusters: each mesh's triangles are put in spatial order (meshoptimizer's spatial sort)
// and cut into chunks of at most kClusterTriangles, each chunk's index order then optimised for
// the post-transform vertex cache. A cluster keeps its object-space bounds and a backface cone,
// so a view can skip the clusters it cannot see: on lavapipe the raster cost of a view is its
// vertex work (DESIGN.md), and a view that sees a third of a room should pay for a third.
// Clusters of one mesh are contiguous in the index buffer, so runs of visible clusters merge
// into one draw.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace ddish::scene {
struct Mesh;
}

namespace ddish::raster {

// 512 is meshopt_computeClusterBounds' limit; larger clusters would also cull more coarsely.
inline constexpr std::uint32_t kClusterTriangles = 512;

struct Cluster {
  std::uint32_t first_index = 0;  // into the packed index buffer of GpuMeshes
  std::uint32_t index_count = 0;
  glm::vec3 min{0.0f};            // object-space bounds of the cluster's vertices
  glm::vec3 max{0.0f};
  // Backface cone (object space): every triangle faces away from an eye e when
  // dot(normalize(apex - e), axis) >= cutoff. cutoff >= 1 means the cone says nothing.
  glm::vec3 cone_apex{0.0f};
  glm::vec3 cone_axis{0.0f, 0.0f, 1.0f};
  float cone_cutoff = 1.0f;
};

struct ClusteredIndices {
  std::vector<std::uint32_t> indices;  // the mesh's triangles in cluster order (mesh-local)
  std::vector<Cluster> clusters;       // first_index relative to base_index given below
};

// Reorders mesh.indices into clusters. base_index is where the mesh's indices start in the
// packed index buffer; the clusters' first_index values include it.
ClusteredIndices cluster_mesh(const scene::Mesh& mesh, std::uint32_t base_index);

// Whether every triangle of the cluster faces away from an eye at `eye` (object space).
bool cone_backfacing(const Cluster& c, const glm::vec3& eye);

}  // namespace ddish::raster
