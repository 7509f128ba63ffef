// From a ray hit to a shading point: world-space triangle, barycentric interpolation of normals,
// UVs (per texture slot: UV set and KHR_texture_transform), vertex colours and tangents,
// textures looked up at the hit (base colour, metallic-roughness, emissive, normal map), double-sided handling, and the self-intersection-safe ray offset. The occlusion
// texture is not read: it is ambient occlusion baked for rasterizers, and paths find occlusion
// themselves.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

#include "trace/bsdf.h"
#include "trace/frame.h"
#include "trace/triangle_record.h"

namespace ddish::scene {
struct Scene;
struct Mesh;
struct Material;
struct TextureSlot;
}  // namespace ddish::scene

namespace ddish::trace {

class TextureSet;

// An instance's object-to-world transform with what shading derives from it, computed once per
// placement rather than at every hit.
struct InstanceTransform {
  glm::mat4 object_to_world{1.0f};
  glm::mat3 normal_matrix{1.0f};  // inverse transpose of the upper 3×3
  bool mirrored = false;          // negative determinant: winding and handedness flip
  static InstanceTransform from(const glm::mat4& m) {
    InstanceTransform t;
    t.object_to_world = m;
    const glm::mat3 m3(m);
    t.normal_matrix = glm::transpose(glm::inverse(m3));
    t.mirrored = glm::determinant(m3) < 0.0f;
    return t;
  }
};

// One triangle of an instance in world space.
struct WorldTriangle {
  glm::vec3 p0{0.0f}, p1{0.0f}, p2{0.0f};
  glm::vec3 cross() const { return glm::cross(p1 - p0, p2 - p0); }  // |.| = 2 × area
  float area() const { return 0.5f * glm::length(cross()); }
};
WorldTriangle world_triangle(const scene::Mesh& mesh, const glm::mat4& xf, int prim);
WorldTriangle world_triangle(const TriangleRecord& tri, const glm::mat4& xf);

// UV area of a triangle in UV set `texcoord` (for mip selection: texels per metre).
float uv_area(const scene::Mesh& mesh, int prim, int texcoord = 0);
// The same from the triangle's record (UV0), or the mesh (UV1).
float uv_area(const TriangleRecord& tri, const scene::Mesh& mesh, int prim, int texcoord);

// The texture coordinate a slot reads at a point of triangle `prim` with vertex weights w
// (w0 + w1 + w2 = 1): its UV set interpolated, then its KHR_texture_transform.
glm::vec2 slot_uv(const scene::Mesh& mesh, const scene::TextureSlot& slot, int prim, const glm::vec3& w);
// The same with UV0 read from the triangle's record.
glm::vec2 slot_uv(const TriangleRecord& tri, const scene::Mesh& mesh, const scene::TextureSlot& slot, int prim,
                  const glm::vec3& w);

// COLOR_0 at a point of triangle `prim` with vertex weights w; white without vertex colours.
glm::vec4 vertex_color(const scene::Mesh& mesh, int prim, const glm::vec3& w);

// Base-colour alpha (factor × texture) at barycentrics (u, v) of a triangle, for alpha testing.
float alpha_at(const scene::Material& material, const TextureSet& textures, const scene::Mesh& mesh,
               const TriangleRecord& tri, int prim, float u, float v, float lod);

struct SurfacePoint {
  glm::vec3 position{0.0f};        // world, from barycentrics (more precise than origin + t·dir)
  glm::vec3 ng{0.0f, 0.0f, 1.0f};  // unit geometric normal, on the ray's side when double-sided
  Frame shading;                   // shading frame (normal-mapped), n on the same side as ng
  glm::vec2 uv{0.0f};
  bool backface = false;  // the ray hit the back of a single-sided surface
  BsdfParams bsdf;
  glm::vec3 emission{0.0f};   // radiance emitted toward the ray (textured)
  bool unlit = false;         // KHR_materials_unlit: emission is the base colour, nothing scatters
  float offset_scale = 0.0f;  // coordinate magnitude for offset_ray_origin
};

struct HitInput {
  const scene::Mesh* mesh = nullptr;
  const scene::Material* material = nullptr;
  const InstanceTransform* transform = nullptr;
  const TriangleRecord* triangle = nullptr;  // the record of mesh triangle `prim` (EmbreeScene::triangle)
  int prim = -1;
  float u = 0.0f, v = 0.0f;                // Embree barycentrics: p = (1-u-v) p0 + u p1 + v p2
  glm::vec3 direction{0.0f, 0.0f, -1.0f};  // the incoming ray's direction (unit)
  float cone_width = 0.0f;                 // ray-cone width at the hit, metres
  int fixed_mip_level = -1;                // >= 0 overrides the cone
};

SurfacePoint make_surface_point(const HitInput& hit, const TextureSet& textures);

// Moves p off its surface along the geometric normal n (unit, pointing to the side the new ray
// leaves from) by a distance proportional to the magnitude of p's coordinates: floating-point
// error in a computed hit point is relative to that magnitude, so the same rule works for
// millimetre and kilometre scenes. Spirit of Wächter & Binder (Ray Tracing Gems, ch. 6).
glm::vec3 offset_ray_origin(const glm::vec3& p, const glm::vec3& n, float magnitude);

// The magnitude offset_ray_origin uses for a point: its largest absolute coordinate.
inline float coordinate_magnitude(const glm::vec3& p) {
  const glm::vec3 a = glm::abs(p);
  return glm::max(a.x, glm::max(a.y, a.z));
}

}  // namespace ddish::trace
