// The Embree 3 view of a scene: one triangle geometry per scene::Mesh, each in its own RTCScene,
// placed in a top-level scene by one RTC_GEOMETRY_TYPE_INSTANCE per scene::Instance (instances
// share geometry; the instance geometry's ID is the scene's instance index). Moving instances
// only re-sets their transforms and re-commits the top level. A deformed mesh (skin, morph
// targets; scene::DeformedMesh) is built for refitting: when its pose_version changes, its
// vertex buffer is rewritten from the posed positions, its BVH refitted and its triangle records
// rebuilt. A scene without animation or deformed meshes whose instances share little (placed triangles at most four times the
// meshes' own) is built flat instead: one world-space triangle geometry per instance, its ID
// the instance index, in one BVH. Rays then skip the instance level (on Sponza, whose mesh boxes
// overlap, ~11 % of the Embree time); shading is the same. Where two coincident triangles tie
// for the closest hit, the two structures may pick different ones (0.42 % of random rays from
// Sponza's probe positions hit another triangle, all but 1 in 8623 at the same distance within
// 1e-4 of it).
//
// Alpha: AlphaMode::Mask materials get intersection and occlusion filter functions that reject
// hits whose base-colour alpha (factor × texture at the hit's UV) is below the cutoff.
// AlphaMode::Blend is stochastic transparency: a hit is kept with probability alpha, decided by
// hashing a per-ray random seed with the hit's instance and triangle, so the expected transmission
// equals what blending a single layer gives, shadows included, and a seed replays exactly.
// Layers decide independently (the hash includes the triangle), so k layers of alpha a transmit
// (1-a)^k; a ray exactly through an edge shared by two triangles meets it twice (measure zero).
// A single-sided Blend surface hit from behind is skipped, as the rasterizer culls it there.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/glm.hpp>

#include "trace/surface.h"
#include "trace/tracer.h"
#include "trace/triangle_record.h"

namespace ddish::scene {
struct Scene;
struct Mesh;
struct Material;
}  // namespace ddish::scene

namespace ddish::trace {

class TextureSet;
class RayRecorder;

struct Hit {
  int instance = -1;  // index into Scene::instances
  int prim = -1;      // triangle of the instance's mesh
  float t = 0.0f;
  float u = 0.0f;  // barycentrics: p = (1-u-v) p0 + u p1 + v p2
  float v = 0.0f;
};

// What alpha-tested lookups need to know about the ray: its random seed (Blend) and its cone
// (the mip level of the alpha texture).
struct RayQuery {
  std::uint32_t alpha_seed = 0;
  float cone_width = 0.0f;   // metres at the ray origin
  float cone_spread = 0.0f;  // radians
  int fixed_mip_level = -1;
};

// An Embree ray-hit record for `ray` (full mask, id and flags 0, time 0), its hit fields set to
// "no hit" so that rtcIntersect1 can fill them.
inline RTCRayHit to_rtc_rayhit(const Ray& ray) {
  RTCRayHit rh{};
  rh.ray.org_x = ray.origin.x;
  rh.ray.org_y = ray.origin.y;
  rh.ray.org_z = ray.origin.z;
  rh.ray.dir_x = ray.direction.x;
  rh.ray.dir_y = ray.direction.y;
  rh.ray.dir_z = ray.direction.z;
  rh.ray.tnear = ray.tmin;
  rh.ray.tfar = ray.tmax;
  rh.ray.mask = 0xFFFFFFFFu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
  for (unsigned& id : rh.hit.instID) id = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

class EmbreeScene {
 public:
  // The scene and the texture set must outlive this object (meshes and textures are read at
  // filter time, not copied).
  EmbreeScene(const scene::Scene& scene, const TextureSet& textures);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  // Re-reads the transforms of `moved` instances (and the vertices of their meshes where the
  // pose changed them) and re-commits the top level. Not concurrent with intersect/occluded.
  void update(const scene::Scene& scene, std::span<const int> moved);

  bool intersect(const Ray& ray, const RayQuery& query, Hit& hit) const;
  // True when something blocks the segment origin + t·direction, t in (tmin, tmax).
  bool occluded(const glm::vec3& origin, const glm::vec3& direction, float tmin, float tmax,
                const RayQuery& query) const;

  // While set, every intersect/occluded call is recorded first (bench/trace_floor); null: off.
  // Not while intersect/occluded run.
  void set_recorder(RayRecorder* recorder) { recorder_ = recorder; }

  const InstanceTransform& transform(int instance) const {
    return transforms_[static_cast<std::size_t>(instance)];
  }

  // One level (every instance's triangles in world space) rather than per-mesh BVHs under an
  // instance level: chosen for scenes without animation where instancing saves little.
  bool flat() const { return flat_; }

  // The shading record of triangle `prim` of scene mesh `mesh` (trace/triangle_record.h).
  const TriangleRecord& triangle(int mesh, int prim) const {
    return mesh_data_[static_cast<std::size_t>(mesh)].triangles[static_cast<std::size_t>(prim)];
  }
  // Rebuilds mesh `m`'s triangle records from its vertex data (the same scene::Mesh, same
  // triangle count): call whenever a mesh's vertices change (skinning, morph targets), together
  // with refitting its Embree geometry (in a flat scene: every instance's world-space copy),
  // before tracing again. Not concurrent with intersect/occluded.
  void update_mesh_triangles(const scene::Mesh& mesh, int m);

  // Per-mesh data the filter functions read (public so the C callbacks can name it).
  struct MeshGeometry {
    const scene::Mesh* mesh = nullptr;
    const scene::Material* material = nullptr;
    const TextureSet* textures = nullptr;
    const EmbreeScene* owner = nullptr;
    std::vector<TriangleRecord> triangles;  // per triangle of the mesh
  };

 private:
  void release();
  // A committed triangle geometry of `mesh`, its vertices placed by `world` (null: object space),
  // with the alpha filters when its material needs them, built at `quality`.
  RTCGeometry new_triangles(const scene::Mesh& mesh, const glm::mat4* world, MeshGeometry& data,
                            RTCBuildQuality quality = RTC_BUILD_QUALITY_HIGH);
  static void write_vertices(const scene::Mesh& mesh, const glm::mat4* world, float* out);
  // Rewrites and refits a deformed mesh whose pose changed since it was last written.
  void reshape(const scene::Scene& scene, int mesh);

  RTCDevice device_ = nullptr;
  RTCScene top_ = nullptr;
  std::vector<RTCScene> mesh_scenes_;          // per scene::Mesh; null for empty meshes
  // Per scene::Instance, null when not placed: its instance geometry, or its world-space triangle
  // geometry when flat.
  std::vector<RTCGeometry> instance_geoms_;
  bool flat_ = false;
  std::vector<InstanceTransform> transforms_;  // per scene::Instance
  std::vector<MeshGeometry> mesh_data_;        // per scene::Mesh (stable addresses: sized once)
  std::vector<RTCGeometry> deformed_geoms_;    // per scene::Mesh; null unless deformed
  std::vector<std::uint64_t> mesh_versions_;   // per scene::Mesh: the pose_version written
  std::string error_;                          // the last error Embree reported
  RayRecorder* recorder_ = nullptr;
};

}  // namespace ddish::trace
