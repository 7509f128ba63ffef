// The draws of one pass: for the views the pass renders, the clusters of every instance that
// some view's frustum meets and that do not face away from every view's eye, merged into runs
// that are contiguous in the index buffer (one vkCmdDrawIndexed per run). Without culling an
// instance is one draw of its whole mesh, as before clusters existed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace ddish::scene {
struct Scene;
}

namespace ddish::raster {

class GpuMeshes;

struct DrawItem {
  std::uint32_t instance = 0;  // index into Scene::instances
  std::uint32_t first_index = 0;
  std::uint32_t index_count = 0;
  std::int32_t vertex_offset = 0;
};

// Counts per pass, summed over the frame (a triangle of a multiview pass counts once).
struct CullStats {
  std::uint64_t clusters_tested = 0;  // clusters of the instances considered
  std::uint64_t clusters_drawn = 0;
  std::uint64_t triangles_drawn = 0;
  std::uint64_t draws = 0;            // vkCmdDrawIndexed calls after merging runs
  CullStats& operator+=(const CullStats& o);
};

struct PassViews {
  std::span<const glm::mat4> view_proj;  // the views one pass draws
  std::span<const glm::vec3> eyes;       // their camera positions (world)
};

// Appends the pass's draws to `out` in the order of `instances` (the caller sorts them by
// material) and adds to `stats`. cull = false: one whole-mesh draw per instance.
void build_draws(const scene::Scene& scene, const GpuMeshes& meshes,
                 std::span<const std::size_t> instances, const PassViews& views, bool cull,
                 std::vector<DrawItem>& out, CullStats& stats);

// The instances with a mesh, by material (so that a pass binds each material's set once);
// blended = false: the opaque and masked ones, true: the BLEND ones (the transparent pass).
std::vector<std::size_t> instances_by_material(const scene::Scene& scene, const GpuMeshes& meshes,
                                               bool blended);

}  // namespace ddish::raster
