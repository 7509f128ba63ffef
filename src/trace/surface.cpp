#include "trace/surface.h"

#include <algorithm>
#include <cmath>

#include "scene/scene.h"
#include "trace/cpu_dispatch.h"
#include "trace/texture_lookup.h"

namespace ddish::trace {

namespace {

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Normalises v, or returns fallback when v is zero or not finite (degenerate input data).
glm::vec3 safe_normalize(const glm::vec3& v, const glm::vec3& fallback) {
  const float len2 = glm::dot(v, v);
  if (!(len2 > 1e-30f) || !std::isfinite(len2)) return fallback;
  return v / std::sqrt(len2);
}

// Texture lod for a footprint (its texture-independent part computed once per hit), or the
// fixed level when one is asked for. A slot's footprint in UV units scales with the square root
// of its UV set's area (per world area) and of its transform's area scale. Slots of one material
// nearly always share both, so the last footprint is kept and reused for the same pair (a square
// root and a logarithm per texture saved; the same numbers).
struct LodRule {
  float cone_width = 0.0f;
  float cos_theta = 1.0f;
  float world_area = 0.0f;
  const scene::Mesh* mesh = nullptr;
  const TriangleRecord* tri = nullptr;
  int prim = -1;
  int fixed = -1;
  mutable int cached_texcoord = -1;
  mutable float cached_scale = 0.0f;
  mutable float cached_log2 = 0.0f;
  float lod(const MipTexture& t, const scene::TextureSlot& slot) const {
    if (fixed >= 0) return static_cast<float>(fixed);
    const float scale = slot.transform.area_scale();
    if (slot.texcoord != cached_texcoord || scale != cached_scale) {
      const float area = uv_area(*tri, *mesh, prim, slot.texcoord) * scale;
      cached_log2 = MipTexture::footprint_log2(cone_width, cos_theta, area, world_area);
      cached_texcoord = slot.texcoord;
      cached_scale = scale;
    }
    return t.lod_for_footprint_log2(cached_log2);
  }
};

// KHR_texture_transform's apply() without its four trigonometric calls when the transform is
// the identity: the same arithmetic on the identity's rows (cos 0 = 1, sin 0 = 0), so the same
// bits, non-finite coordinates included.
glm::vec2 apply_transform(const scene::TextureTransform& xf, glm::vec2 uv) {
  if (!xf.identity()) return xf.apply(uv);
  const glm::vec3 h(uv, 1.0f);
  return {glm::dot(glm::vec3(1.0f, 0.0f, 0.0f), h), glm::dot(glm::vec3(-0.0f, 1.0f, 0.0f), h)};
}

}  // namespace

DDISH_CPU_DISPATCH
WorldTriangle world_triangle(const scene::Mesh& mesh, const glm::mat4& xf, int prim) {
  const std::uint32_t* idx = &mesh.indices[static_cast<std::size_t>(prim) * 3];
  auto w = [&](std::uint32_t i) { return glm::vec3(xf * glm::vec4(mesh.positions[i], 1.0f)); };
  return {w(idx[0]), w(idx[1]), w(idx[2])};
}

DDISH_CPU_DISPATCH
WorldTriangle world_triangle(const TriangleRecord& tri, const glm::mat4& xf) {
  auto w = [&](const glm::vec3& p) { return glm::vec3(xf * glm::vec4(p, 1.0f)); };
  return {w(tri.p[0]), w(tri.p[1]), w(tri.p[2])};
}

float uv_area(const TriangleRecord& tri, const scene::Mesh& mesh, int prim, int texcoord) {
  return texcoord == 1 ? uv_area(mesh, prim, 1) : tri.uv_area;  // Mesh::uv_set's rule
}

float uv_area(const scene::Mesh& mesh, int prim, int texcoord) {
  const std::vector<glm::vec2>& uvs = mesh.uv_set(texcoord);
  if (uvs.size() != mesh.positions.size()) return 0.0f;
  const std::uint32_t* idx = &mesh.indices[static_cast<std::size_t>(prim) * 3];
  const glm::vec2 a = uvs[idx[1]] - uvs[idx[0]];
  const glm::vec2 b = uvs[idx[2]] - uvs[idx[0]];
  return 0.5f * std::abs(a.x * b.y - a.y * b.x);
}

glm::vec2 slot_uv(const scene::Mesh& mesh, const scene::TextureSlot& slot, int prim, const glm::vec3& w) {
  const std::vector<glm::vec2>& uvs = mesh.uv_set(slot.texcoord);
  glm::vec2 uv(0.0f);
  if (uvs.size() == mesh.positions.size()) {
    const std::uint32_t* idx = &mesh.indices[static_cast<std::size_t>(prim) * 3];
    uv = uvs[idx[0]] * w.x + uvs[idx[1]] * w.y + uvs[idx[2]] * w.z;
  }
  return apply_transform(slot.transform, uv);
}

glm::vec2 slot_uv(const TriangleRecord& tri, const scene::Mesh& mesh, const scene::TextureSlot& slot, int prim,
                  const glm::vec3& w) {
  if (slot.texcoord == 1) return slot_uv(mesh, slot, prim, w);  // Mesh::uv_set's rule
  glm::vec2 uv(0.0f);
  if (tri.has(TriangleRecord::kUvs)) uv = tri.uv[0] * w.x + tri.uv[1] * w.y + tri.uv[2] * w.z;
  return apply_transform(slot.transform, uv);
}

glm::vec4 vertex_color(const scene::Mesh& mesh, int prim, const glm::vec3& w) {
  if (mesh.colors.size() != mesh.positions.size()) return glm::vec4(1.0f);
  const std::uint32_t* idx = &mesh.indices[static_cast<std::size_t>(prim) * 3];
  return mesh.colors[idx[0]] * w.x + mesh.colors[idx[1]] * w.y + mesh.colors[idx[2]] * w.z;
}

float alpha_at(const scene::Material& material, const TextureSet& textures, const scene::Mesh& mesh,
               const TriangleRecord& tri, int prim, float u, float v, float lod) {
  const glm::vec3 w(1.0f - u - v, u, v);
  float alpha = material.base_color.a * vertex_color(mesh, prim, w).a;
  if (const MipTexture* tex = textures.get(material.base_color_texture.texture)) {
    const glm::vec2 uv = slot_uv(tri, mesh, material.base_color_texture, prim, w);
    alpha *= tex->sample(uv, lod, false, wrap_of(material.base_color_texture)).a;
  }
  return alpha;
}

DDISH_CPU_DISPATCH
SurfacePoint make_surface_point(const HitInput& hit, const TextureSet& textures) {
  const scene::Mesh& mesh = *hit.mesh;
  const scene::Material& mat = *hit.material;
  const TriangleRecord& rec = *hit.triangle;
  const float u = hit.u;
  const float v = hit.v;
  SurfacePoint sp;

  const InstanceTransform& xf = *hit.transform;
  const WorldTriangle tri = world_triangle(rec, xf.object_to_world);
  sp.position = tri.p0 * (1.0f - u - v) + tri.p1 * u + tri.p2 * v;
  sp.offset_scale =
      std::max({coordinate_magnitude(tri.p0), coordinate_magnitude(tri.p1), coordinate_magnitude(tri.p2)});
  const glm::vec3 wo = -hit.direction;
  // A zero-area triangle has no normal: face the ray so shading stays finite.
  sp.ng = safe_normalize(tri.cross(), wo);
  // glTF: a mirroring transform makes clockwise triangles the front faces.
  if (xf.mirrored) sp.ng = -sp.ng;

  const glm::mat3 m3(xf.object_to_world);

  glm::vec3 n_obj =
      rec.has(TriangleRecord::kNormals) ? TriangleRecord::interpolate(rec.n, u, v) : glm::vec3(0.0f);
  glm::vec3 n = safe_normalize(xf.normal_matrix * n_obj, sp.ng);
  if (glm::dot(n, sp.ng) < 0.0f) n = -n;  // vertex normals against the winding: trust the winding
  if (rec.has(TriangleRecord::kUvs)) sp.uv = TriangleRecord::interpolate(rec.uv, u, v);

  // Tangent frame: the interpolated glTF tangent, Gram-Schmidt against n; the bitangent's
  // handedness is the tangent's w, flipped by mirroring transforms (det < 0).
  glm::vec3 t(0.0f);
  float handed = 1.0f;
  if (rec.has(TriangleRecord::kTangents)) {
    const glm::vec4 t4 = TriangleRecord::interpolate(rec.t, u, v);
    t = m3 * glm::vec3(t4);
    handed = (t4.w < 0.0f ? -1.0f : 1.0f) * (xf.mirrored ? -1.0f : 1.0f);
  }
  t = t - n * glm::dot(n, t);
  Frame frame = Frame::from_normal(n);
  if (glm::dot(t, t) > 1e-20f && finite(t)) {
    frame.t = glm::normalize(t);
    frame.b = glm::cross(n, frame.t) * handed;
  }

  LodRule rule;
  rule.fixed = hit.fixed_mip_level;
  rule.cone_width = hit.cone_width;
  rule.cos_theta = glm::dot(sp.ng, wo);
  rule.world_area = tri.area();
  rule.mesh = &mesh;
  rule.tri = &rec;
  rule.prim = hit.prim;
  const glm::vec3 weights(1.0f - u - v, u, v);
  auto lookup = [&](const MipTexture& tex, const scene::TextureSlot& slot, bool srgb) {
    return tex.sample(slot_uv(rec, mesh, slot, hit.prim, weights), rule.lod(tex, slot), srgb, wrap_of(slot));
  };

  if (const MipTexture* tex = textures.get(mat.normal_texture.texture)) {
    const glm::vec3 c =
        glm::vec3(lookup(*tex, mat.normal_texture, false)) * 2.0f - 1.0f;
    const glm::vec3 ts(c.x * mat.normal_scale, c.y * mat.normal_scale, c.z);
    n = safe_normalize(frame.t * ts.x + frame.b * ts.y + frame.n * ts.z, n);
  }
  // Sidedness: double-sided surfaces turn their frame to the ray; single-sided ones report a
  // back face (the inside of a closed object).
  const bool back = glm::dot(sp.ng, wo) < 0.0f;
  if (back && mat.double_sided) {
    sp.ng = -sp.ng;
    n = -n;
  }
  sp.backface = back && !mat.double_sided;
  // A normal map (or bent vertex normals) can turn the shading normal away from a viewer the
  // geometry faces; such a point would shade black, so it falls back to the geometric normal.
  if (!sp.backface && glm::dot(n, wo) <= 0.0f) n = sp.ng;
  glm::vec3 tangent = frame.t - n * glm::dot(n, frame.t);
  sp.shading.n = n;
  if (glm::dot(tangent, tangent) > 1e-20f) {
    sp.shading.t = glm::normalize(tangent);
    sp.shading.b = glm::cross(n, sp.shading.t);
  } else {
    sp.shading = Frame::from_normal(n);
  }

  // COLOR_0 multiplies the base colour factor and texture (glTF).
  glm::vec4 base = mat.base_color * vertex_color(mesh, hit.prim, weights);
  if (const MipTexture* tex = textures.get(mat.base_color_texture.texture)) {
    base *= lookup(*tex, mat.base_color_texture, true);
  }
  float metallic = mat.metallic;
  float roughness = mat.roughness;
  if (const MipTexture* tex = textures.get(mat.metallic_roughness_texture.texture)) {
    const glm::vec4 mr = lookup(*tex, mat.metallic_roughness_texture, false);
    roughness *= mr.g;
    metallic *= mr.b;
  }
  sp.bsdf.base_color = glm::clamp(glm::vec3(base), 0.0f, 1.0f);
  sp.bsdf.metallic = std::clamp(metallic, 0.0f, 1.0f);
  sp.bsdf.roughness = std::clamp(roughness, 0.0f, 1.0f);
  sp.bsdf.dielectric_f0 = mat.dielectric_f0();  // KHR_materials_ior / KHR_materials_specular
  sp.bsdf.specular = mat.specular;

  if (mat.is_emissive() && !sp.backface) {
    glm::vec3 e = mat.emission();
    if (const MipTexture* tex = textures.get(mat.emissive_texture.texture)) {
      e *= glm::vec3(lookup(*tex, mat.emissive_texture, true));
    }
    sp.emission = e;
  }
  // KHR_materials_unlit: the base colour is what the surface shows, its emission included.
  if (mat.unlit) {
    sp.unlit = true;
    sp.emission = sp.backface ? glm::vec3(0.0f) : sp.bsdf.base_color;
  }
  return sp;
}

glm::vec3 offset_ray_origin(const glm::vec3& p, const glm::vec3& n, float magnitude) {
  // 2^-17 of the magnitude is 64 float ulps at that magnitude: well above the few ulps of error
  // in an interpolated hit point and in Embree's intersection distance, so the new ray starts
  // strictly on n's side of the surface it leaves. The floor keeps points at the origin moving.
  const float m = std::max(std::max(magnitude, coordinate_magnitude(p)), 1e-30f);
  return p + n * (m * 0x1p-17f);
}

}  // namespace ddish::trace
