#include "raster/draw_list.h"

#include <algorithm>

#include "raster/clusters.h"
#include "raster/frustum_cull.h"
#include "raster/gpu_meshes.h"
#include "scene/scene.h"

namespace ddish::raster {

CullStats& CullStats::operator+=(const CullStats& o) {
  clusters_tested += o.clusters_tested;
  clusters_drawn += o.clusters_drawn;
  triangles_drawn += o.triangles_drawn;
  draws += o.draws;
  return *this;
}

namespace {

void append(std::vector<DrawItem>& out, CullStats& stats, std::uint32_t instance,
            std::uint32_t first_index, std::uint32_t index_count, std::int32_t vertex_offset) {
  if (!out.empty()) {
    DrawItem& last = out.back();
    // Consecutive visible clusters of one instance are one range of the index buffer.
    if (last.instance == instance && last.first_index + last.index_count == first_index) {
      last.index_count += index_count;
      return;
    }
  }
  out.push_back({instance, first_index, index_count, vertex_offset});
  ++stats.draws;
}

}  // namespace

void build_draws(const scene::Scene& scene, const GpuMeshes& meshes,
                 std::span<const std::size_t> instances, const PassViews& views, bool cull,
                 std::vector<DrawItem>& out, CullStats& stats) {
  std::vector<Frustum> world;
  for (const glm::mat4& m : views.view_proj) world.push_back(Frustum::from_view_proj(m));
  std::vector<Frustum> object(world.size());
  std::vector<glm::vec3> eyes(views.eyes.size());

  for (std::size_t i : instances) {
    const scene::Instance& inst = scene.instances[i];
    const MeshRange& range = meshes.range(inst.mesh);
    const std::span<const Cluster> clusters = meshes.clusters(inst.mesh);
    const auto index = static_cast<std::uint32_t>(i);
    stats.clusters_tested += clusters.size();
    if (range.index_count == 0) continue;
    if (!cull) {
      append(out, stats, index, range.first_index, range.index_count, range.vertex_offset);
      stats.clusters_drawn += clusters.size();
      stats.triangles_drawn += range.index_count / 3;
      continue;
    }
    const scene::Mesh& mesh = scene.meshes[static_cast<std::size_t>(inst.mesh)];
    for (std::size_t v = 0; v < world.size(); ++v) object[v] = world[v].in_object_space(inst.transform);
    if (!any_meets(object, mesh.bounds.min, mesh.bounds.max)) continue;

    // Cones are about counter-clockwise front faces: a mirroring transform swaps the sides, and
    // double-sided materials draw both, so neither may lose clusters to a cone.
    const bool mirrored = glm::determinant(glm::mat3(inst.transform)) < 0.0f;
    const bool cones = !mirrored && !scene.material_of(mesh).double_sided;
    if (cones) {
      // Facing is an orientation test, which an affine map with positive determinant keeps:
      // the object-space cone against the object-space eye is exact.
      const glm::mat4 to_object = glm::inverse(inst.transform);
      for (std::size_t v = 0; v < eyes.size(); ++v) eyes[v] = glm::vec3(to_object * glm::vec4(views.eyes[v], 1.0f));
    }
    for (const Cluster& c : clusters) {
      if (!any_meets(object, c.min, c.max)) continue;
      if (cones) {
        bool all_back = true;
        for (const glm::vec3& e : eyes)
          if (!cone_backfacing(c, e)) {
            all_back = false;
            break;
          }
        if (all_back) continue;
      }
      append(out, stats, index, c.first_index, c.index_count, range.vertex_offset);
      ++stats.clusters_drawn;
      stats.triangles_drawn += c.index_count / 3;
    }
  }
}

std::vector<std::size_t> instances_by_material(const scene::Scene& scene, const GpuMeshes& meshes,
                                               bool blended) {
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < scene.instances.size(); ++i) {
    const int mesh = scene.instances[i].mesh;
    if (mesh < 0 || static_cast<std::size_t>(mesh) >= meshes.mesh_count()) continue;
    const bool blend = scene.material_of(scene.meshes[static_cast<std::size_t>(mesh)]).alpha_mode ==
                       scene::AlphaMode::Blend;
    if (blend == blended) order.push_back(i);
  }
  auto material_of = [&](std::size_t i) {
    return scene.meshes[static_cast<std::size_t>(scene.instances[i].mesh)].material;
  };
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return material_of(a) < material_of(b); });
  return order;
}

}  // namespace ddish::raster
