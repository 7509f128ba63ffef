#include "trace/surface.h"

#include <algorithm>
#include <cmath>

#include "scene/scene.h"
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

template <typename T>
T interpolate(const std::vector<T>& attr, const std::uint32_t* idx, float u, float v) {
  return attr[idx[0]] * (1.0f - u - v) + attr[idx[1]] * u + attr[idx[2]] * v;
}

// Texture lod for a footprint (its texture-independent part computed once per hit), or the
// fixed level when one is asked for.
struct LodRule {
  float log2_uv_footprint = 0.0f;
  int fixed = -1;
  float lod(const MipTexture& t) const {
    return fixed >= 0 ? static_cast<float>(fixed) : t.lod_for_footprint_log2(log2_uv_footprint);
  }
};

}  // namespace

WorldTriangle world_triangle(const scene::Mesh& mesh, const glm::mat4& xf, int prim) {
  const std::uint32_t* idx = &mesh.indices[static_cast<std::size_t>(prim) * 3];
  auto w = [&](std::uint32_t i) { return glm::vec3(xf * glm::vec4(mesh.positions[i], 1.0f)); };
  return {w(idx[0]), w(idx[1]), w(idx[2])};
}

float uv_area(const scene::Mesh& mesh, int prim) {
  if (mesh.uvs.size() != mesh.positions.size()) return 0.0f;
  const std::uint32_t* idx = &mesh.indices[static_cast<std::size_t>(prim) * 3];
  const glm::vec2 a = mesh.uvs[idx[1]] - mesh.uvs[idx[0]];
  const glm::vec2 b = mesh.uvs[idx[2]] - mesh.uvs[idx[0]];
  return 0.5f * std::abs(a.x * b.y - a.y * b.x);
}

float alpha_at(const scene::Material& material, const TextureSet& textures, const scene::Mesh& mesh, int prim,
               float u, float v, float lod) {
  float alpha = material.base_color.a;
  const MipTexture* tex = textures.get(material.base_color_texture.texture);
  if (tex != nullptr && mesh.uvs.size() == mesh.positions.size()) {
    const std::uint32_t* idx = &mesh.indices[static_cast<std::size_t>(prim) * 3];
    alpha *=
        tex->sample(interpolate(mesh.uvs, idx, u, v), lod, false, wrap_of(material.base_color_texture)).a;
  }
  return alpha;
}

SurfacePoint make_surface_point(const HitInput& hit, const TextureSet& textures) {
  const scene::Mesh& mesh = *hit.mesh;
  const scene::Material& mat = *hit.material;
  const std::uint32_t* idx = &mesh.indices[static_cast<std::size_t>(hit.prim) * 3];
  const float u = hit.u;
  const float v = hit.v;
  SurfacePoint sp;

  const InstanceTransform& xf = *hit.transform;
  const WorldTriangle tri = world_triangle(mesh, xf.object_to_world, hit.prim);
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
      mesh.normals.size() == mesh.positions.size() ? interpolate(mesh.normals, idx, u, v) : glm::vec3(0.0f);
  glm::vec3 n = safe_normalize(xf.normal_matrix * n_obj, sp.ng);
  if (glm::dot(n, sp.ng) < 0.0f) n = -n;  // vertex normals against the winding: trust the winding
  if (mesh.uvs.size() == mesh.positions.size()) sp.uv = interpolate(mesh.uvs, idx, u, v);

  // Tangent frame: the interpolated glTF tangent, Gram-Schmidt against n; the bitangent's
  // handedness is the tangent's w, flipped by mirroring transforms (det < 0).
  glm::vec3 t(0.0f);
  float handed = 1.0f;
  if (mesh.tangents.size() == mesh.positions.size()) {
    const glm::vec4 t4 = interpolate(mesh.tangents, idx, u, v);
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
  if (rule.fixed < 0) {
    rule.log2_uv_footprint =
        MipTexture::footprint_log2(hit.cone_width, glm::dot(sp.ng, wo), uv_area(mesh, hit.prim), tri.area());
  }

  if (const MipTexture* tex = textures.get(mat.normal_texture.texture)) {
    const glm::vec3 c =
        glm::vec3(tex->sample(sp.uv, rule.lod(*tex), false, wrap_of(mat.normal_texture))) * 2.0f - 1.0f;
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

  glm::vec4 base = mat.base_color;
  if (const MipTexture* tex = textures.get(mat.base_color_texture.texture)) {
    base *= tex->sample(sp.uv, rule.lod(*tex), true, wrap_of(mat.base_color_texture));
  }
  float metallic = mat.metallic;
  float roughness = mat.roughness;
  if (const MipTexture* tex = textures.get(mat.metallic_roughness_texture.texture)) {
    const glm::vec4 mr = tex->sample(sp.uv, rule.lod(*tex), false, wrap_of(mat.metallic_roughness_texture));
    roughness *= mr.g;
    metallic *= mr.b;
  }
  sp.bsdf.base_color = glm::clamp(glm::vec3(base), 0.0f, 1.0f);
  sp.bsdf.metallic = std::clamp(metallic, 0.0f, 1.0f);
  sp.bsdf.roughness = std::clamp(roughness, 0.0f, 1.0f);

  if (mat.is_emissive() && !sp.backface) {
    glm::vec3 e = mat.emission();
    if (const MipTexture* tex = textures.get(mat.emissive_texture.texture)) {
      e *= glm::vec3(tex->sample(sp.uv, rule.lod(*tex), true, wrap_of(mat.emissive_texture)));
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
