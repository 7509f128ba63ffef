#include "trace/embree_scene.h"

#include <cstring>
#include <stdexcept>
#include <string>

#include "scene/scene.h"
#include "trace/ray_recorder.h"
#include "trace/surface.h"
#include "trace/texture_lookup.h"

namespace ddish::trace {

namespace {

// RTCIntersectContext extended with what the filters need; Embree hands the filter the pointer
// it was given, so the standard context must come first.
struct FilterContext {
  RTCIntersectContext rtc;
  const RayQuery* query;
  glm::vec3 direction;  // the ray's, in world space (filters may see it in instance space)
};

// A uniform number in [0, 1) from the ray's seed and the hit's identity (Blend transparency).
float hash_uniform(std::uint32_t seed, std::uint32_t instance, std::uint32_t prim) {
  std::uint64_t z = (static_cast<std::uint64_t>(seed) << 32) ^
                    (static_cast<std::uint64_t>(instance) * 0x9E3779B1u) ^
                    (static_cast<std::uint64_t>(prim) * 0x85EBCA77C2B2AE63ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return static_cast<float>(z >> 40) * 0x1p-24f;
}

void alpha_filter(const RTCFilterFunctionNArguments* args) {
  const auto* geom = static_cast<const EmbreeScene::MeshGeometry*>(args->geometryUserPtr);
  const auto* ctx = reinterpret_cast<const FilterContext*>(args->context);
  const RayQuery& q = *ctx->query;
  const scene::Material& mat = *geom->material;
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const unsigned instance = geom->owner->flat() ? RTCHitN_geomID(args->hit, args->N, i)
                                                   : RTCHitN_instID(args->hit, args->N, i, 0);
    const auto prim = static_cast<int>(RTCHitN_primID(args->hit, args->N, i));
    const float u = RTCHitN_u(args->hit, args->N, i);
    const float v = RTCHitN_v(args->hit, args->N, i);
    // Mip level from the cone at the hit; the obliquity term is left out here (the hit normal is
    // not at hand), which selects a slightly sharper level than shading does at grazing angles.
    float lod = static_cast<float>(q.fixed_mip_level);
    if (q.fixed_mip_level < 0) {
      lod = 0.0f;
      const MipTexture* tex = geom->textures->get(mat.base_color_texture.texture);
      if (tex != nullptr && instance != RTC_INVALID_GEOMETRY_ID) {
        const float t = RTCRayN_tfar(args->ray, args->N, i);
        const float width = q.cone_width + q.cone_spread * t;
        const glm::mat4& xf = geom->owner->transform(static_cast<int>(instance)).object_to_world;
        const TriangleRecord& tri = geom->triangles[static_cast<std::size_t>(prim)];
        const float area = world_triangle(tri, xf).area();
        const scene::TextureSlot& slot = mat.base_color_texture;
        lod = tex->lod_for_footprint(
            width, 1.0f, uv_area(tri, *geom->mesh, prim, slot.texcoord) * slot.transform.area_scale(), area);
      }
    }
    // A single-sided BLEND surface seen from behind is not there, as the rasterizer culls its
    // back faces: the ray passes (a closed opaque object's back faces still end paths).
    if (mat.alpha_mode == scene::AlphaMode::Blend && !mat.double_sided && instance != RTC_INVALID_GEOMETRY_ID) {
      const InstanceTransform& xf = geom->owner->transform(static_cast<int>(instance));
      glm::vec3 ng =
          world_triangle(geom->triangles[static_cast<std::size_t>(prim)], xf.object_to_world).cross();
      if (xf.mirrored) ng = -ng;
      if (glm::dot(ng, ctx->direction) > 0.0f) {
        args->valid[i] = 0;
        continue;
      }
    }
    const float alpha = alpha_at(mat, *geom->textures, *geom->mesh, geom->triangles[static_cast<std::size_t>(prim)],
                                 prim, u, v, lod);
    const bool keep = mat.alpha_mode == scene::AlphaMode::Mask
                          ? alpha >= mat.alpha_cutoff
                          : hash_uniform(q.alpha_seed, instance, static_cast<std::uint32_t>(prim)) < alpha;
    if (!keep) args->valid[i] = 0;
  }
}

// Copies the mesh's (current) positions into the geometry's vertex buffer.
void error_callback(void* user, RTCError code, const char* message) {
  auto* last = static_cast<std::string*>(user);
  *last = "Embree error " + std::to_string(static_cast<int>(code)) + ": " + (message ? message : "");
}

}  // namespace

EmbreeScene::EmbreeScene(const scene::Scene& scene, const TextureSet& textures) {
  device_ = rtcNewDevice(nullptr);
  if (device_ == nullptr) throw std::runtime_error("cannot create an Embree device");
  rtcSetDeviceErrorFunction(device_, error_callback, &error_);

  // Flat when nothing in the scene is animated and instancing saves little: the placed triangles
  // are at most four times the meshes' own (memory grows at most fourfold). On Sponza (2.3 times)
  // the flat scene cut bench/trace_floor's replay through this scene by ~11 % of its CPU time and
  // the probe update by ~7 %: its meshes' boxes overlap, so a ray entered many instances.
  std::size_t own = 0, placed = 0;
  for (const scene::Mesh& mesh : scene.meshes) own += mesh.triangle_count();
  for (const scene::Instance& inst : scene.instances) {
    if (inst.mesh >= 0 && static_cast<std::size_t>(inst.mesh) < scene.meshes.size())
      placed += scene.meshes[static_cast<std::size_t>(inst.mesh)].triangle_count();
  }
  flat_ = scene.animations.empty() && scene.deformed.empty() && placed <= 4 * own;

  mesh_data_.resize(scene.meshes.size());
  mesh_scenes_.assign(scene.meshes.size(), nullptr);
  deformed_geoms_.assign(scene.meshes.size(), nullptr);
  mesh_versions_.assign(scene.meshes.size(), 0);
  std::vector<bool> deformed(scene.meshes.size(), false);
  for (const scene::DeformedMesh& d : scene.deformed) deformed[static_cast<std::size_t>(d.mesh)] = true;
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    const scene::Mesh& mesh = scene.meshes[m];
    const scene::Material& mat = scene.material_of(mesh);
    mesh_data_[m] = {&mesh, &mat, &textures, this, {}};
    if (mesh.triangle_count() == 0 || mesh.positions.empty()) continue;
    mesh_data_[m].triangles = make_triangle_records(mesh);

    if (flat_) continue;  // each instance gets its own world-space geometry below
    // A deformed mesh (skin, morph targets) gets new vertices whenever its pose changes: its
    // BVH is refitted then, which keeps the tree's topology and recomputes its boxes (Embree
    // honours a geometry's quality in a scene of quality LOW).
    RTCScene s = rtcNewScene(device_);
    rtcSetSceneFlags(s, deformed[m] ? RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_DYNAMIC : RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(s, deformed[m] ? RTC_BUILD_QUALITY_LOW : RTC_BUILD_QUALITY_HIGH);
    RTCGeometry geom = new_triangles(mesh, nullptr, mesh_data_[m],
                                     deformed[m] ? RTC_BUILD_QUALITY_REFIT : RTC_BUILD_QUALITY_HIGH);
    mesh_versions_[m] = mesh.pose_version;
    rtcAttachGeometryByID(s, geom, 0);
    if (deformed[m])
      deformed_geoms_[m] = geom;  // kept to rewrite its vertices (released with the scene)
    else
      rtcReleaseGeometry(geom);
    rtcCommitScene(s);
    mesh_scenes_[m] = s;
  }

  instance_geoms_.assign(scene.instances.size(), nullptr);
  transforms_.resize(scene.instances.size());
  if (flat_) {
    // One level: every instance's triangles in world space, geometry ID = instance index.
    top_ = rtcNewScene(device_);
    rtcSetSceneFlags(top_, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(top_, RTC_BUILD_QUALITY_HIGH);
    for (std::size_t i = 0; i < scene.instances.size(); ++i) {
      const scene::Instance& inst = scene.instances[i];
      transforms_[i] = InstanceTransform::from(inst.transform);
      if (inst.mesh < 0 || static_cast<std::size_t>(inst.mesh) >= mesh_data_.size() ||
          mesh_data_[static_cast<std::size_t>(inst.mesh)].triangles.empty()) {
        continue;
      }
      const auto m = static_cast<std::size_t>(inst.mesh);
      RTCGeometry g = new_triangles(scene.meshes[m], &inst.transform, mesh_data_[m]);
      rtcAttachGeometryByID(top_, g, static_cast<unsigned>(i));
      instance_geoms_[i] = g;
    }
    rtcCommitScene(top_);
    if (!error_.empty()) {
      release();
      throw std::runtime_error(error_);
    }
    return;
  }

  // The top level changes when instances move: a dynamic scene rebuilds fast over its (few
  // hundred at most) instance boxes.
  top_ = rtcNewScene(device_);
  rtcSetSceneFlags(top_, RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_DYNAMIC);
  rtcSetSceneBuildQuality(top_, RTC_BUILD_QUALITY_LOW);
  for (std::size_t i = 0; i < scene.instances.size(); ++i) {
    const scene::Instance& inst = scene.instances[i];
    transforms_[i] = InstanceTransform::from(inst.transform);
    if (inst.mesh < 0 || static_cast<std::size_t>(inst.mesh) >= mesh_scenes_.size() ||
        mesh_scenes_[static_cast<std::size_t>(inst.mesh)] == nullptr) {
      continue;
    }
    RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(g, mesh_scenes_[static_cast<std::size_t>(inst.mesh)]);
    rtcSetGeometryTimeStepCount(g, 1);
    rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &transforms_[i].object_to_world[0][0]);
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(top_, g, static_cast<unsigned>(i));
    instance_geoms_[i] = g;
  }
  rtcCommitScene(top_);
  if (!error_.empty()) {
    release();
    throw std::runtime_error(error_);
  }
}

RTCGeometry EmbreeScene::new_triangles(const scene::Mesh& mesh, const glm::mat4* world, MeshGeometry& data,
                                       RTCBuildQuality quality) {
  RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* verts = static_cast<float*>(rtcSetNewGeometryBuffer(
      geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.positions.size()));
  write_vertices(mesh, world, verts);
  auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
      geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), mesh.triangle_count()));
  std::memcpy(idx, mesh.indices.data(), mesh.triangle_count() * 3 * sizeof(unsigned));
  rtcSetGeometryBuildQuality(geom, quality);
  if (data.material->alpha_mode != scene::AlphaMode::Opaque) {
    rtcSetGeometryUserData(geom, &data);
    rtcSetGeometryIntersectFilterFunction(geom, alpha_filter);
    rtcSetGeometryOccludedFilterFunction(geom, alpha_filter);
  }
  rtcCommitGeometry(geom);
  return geom;
}

void EmbreeScene::write_vertices(const scene::Mesh& mesh, const glm::mat4* world, float* out) {
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::vec3 p = world ? glm::vec3(*world * glm::vec4(mesh.positions[i], 1.0f)) : mesh.positions[i];
    std::memcpy(out + 3 * i, &p, 3 * sizeof(float));
  }
}

EmbreeScene::~EmbreeScene() { release(); }

void EmbreeScene::release() {
  for (RTCGeometry& g : instance_geoms_) {
    if (g != nullptr) rtcReleaseGeometry(g);
    g = nullptr;
  }
  if (top_ != nullptr) rtcReleaseScene(top_);
  top_ = nullptr;
  for (RTCGeometry& g : deformed_geoms_) {
    if (g != nullptr) rtcReleaseGeometry(g);
    g = nullptr;
  }
  for (RTCScene& s : mesh_scenes_) {
    if (s != nullptr) rtcReleaseScene(s);
    s = nullptr;
  }
  if (device_ != nullptr) rtcReleaseDevice(device_);
  device_ = nullptr;
}

void EmbreeScene::update_mesh_triangles(const scene::Mesh& mesh, int m) {
  MeshGeometry& g = mesh_data_.at(static_cast<std::size_t>(m));
  if (g.mesh != &mesh || g.triangles.size() != mesh.triangle_count())
    throw std::invalid_argument("update_mesh_triangles: not the mesh this scene was built with");
  g.triangles = make_triangle_records(mesh);
}

void EmbreeScene::update(const scene::Scene& scene, std::span<const int> moved) {
  bool changed = false;
  for (int i : moved) {
    if (i < 0 || static_cast<std::size_t>(i) >= transforms_.size() ||
        static_cast<std::size_t>(i) >= scene.instances.size()) {
      continue;
    }
    const auto k = static_cast<std::size_t>(i);
    reshape(scene, scene.instances[k].mesh);
    transforms_[k] = InstanceTransform::from(scene.instances[k].transform);
    if (instance_geoms_[k] == nullptr) continue;
    if (flat_) {  // its world-space vertices again
      const scene::Mesh& mesh = scene.meshes[static_cast<std::size_t>(scene.instances[k].mesh)];
      auto* verts = static_cast<float*>(rtcGetGeometryBufferData(instance_geoms_[k], RTC_BUFFER_TYPE_VERTEX, 0));
      write_vertices(mesh, &scene.instances[k].transform, verts);
      rtcUpdateGeometryBuffer(instance_geoms_[k], RTC_BUFFER_TYPE_VERTEX, 0);
      rtcCommitGeometry(instance_geoms_[k]);
      changed = true;
      continue;
    }
    rtcSetGeometryTransform(instance_geoms_[k], 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR,
                            &transforms_[k].object_to_world[0][0]);
    rtcCommitGeometry(instance_geoms_[k]);
    changed = true;
  }
  if (changed) rtcCommitScene(top_);
}

void EmbreeScene::reshape(const scene::Scene& scene, int mesh) {
  if (mesh < 0 || static_cast<std::size_t>(mesh) >= deformed_geoms_.size()) return;
  const auto m = static_cast<std::size_t>(mesh);
  RTCGeometry geom = deformed_geoms_[m];
  const scene::Mesh& posed = scene.meshes[m];
  if (geom == nullptr || mesh_versions_[m] == posed.pose_version) return;
  write_vertices(posed, nullptr, static_cast<float*>(rtcGetGeometryBufferData(geom, RTC_BUFFER_TYPE_VERTEX, 0)));
  rtcUpdateGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0);
  rtcCommitGeometry(geom);
  rtcCommitScene(mesh_scenes_[m]);
  update_mesh_triangles(posed, mesh);
  mesh_versions_[m] = posed.pose_version;
}

bool EmbreeScene::intersect(const Ray& ray, const RayQuery& query, Hit& hit) const {
  if (recorder_ != nullptr) {
    recorder_->record({ray.origin, ray.tmin, ray.direction, ray.tmax, query.alpha_seed, query.cone_width,
                       query.cone_spread, false});
  }
  FilterContext ctx;
  rtcInitIntersectContext(&ctx.rtc);
  ctx.rtc.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
  ctx.query = &query;
  ctx.direction = ray.direction;
  RTCRayHit rh = to_rtc_rayhit(ray);
  rtcIntersect1(top_, &ctx.rtc, &rh);
  const unsigned instance = flat_ ? rh.hit.geomID : rh.hit.instID[0];
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID || instance == RTC_INVALID_GEOMETRY_ID) return false;
  hit.instance = static_cast<int>(instance);
  hit.prim = static_cast<int>(rh.hit.primID);
  hit.t = rh.ray.tfar;
  hit.u = rh.hit.u;
  hit.v = rh.hit.v;
  return true;
}

bool EmbreeScene::occluded(const glm::vec3& origin, const glm::vec3& direction, float tmin, float tmax,
                           const RayQuery& query) const {
  if (recorder_ != nullptr) {
    recorder_->record(
        {origin, tmin, direction, tmax, query.alpha_seed, query.cone_width, query.cone_spread, true});
  }
  FilterContext ctx;
  rtcInitIntersectContext(&ctx.rtc);
  ctx.rtc.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
  ctx.query = &query;
  ctx.direction = direction;
  RTCRay r;
  r.org_x = origin.x;
  r.org_y = origin.y;
  r.org_z = origin.z;
  r.dir_x = direction.x;
  r.dir_y = direction.y;
  r.dir_z = direction.z;
  r.tnear = tmin;
  r.tfar = tmax;
  r.time = 0.0f;
  r.mask = 0xFFFFFFFFu;
  r.id = 0;
  r.flags = 0;
  rtcOccluded1(top_, &ctx.rtc, &r);
  return r.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
}

}  // namespace ddish::trace
