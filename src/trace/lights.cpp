#include "trace/lights.h"

#include <algorithm>
#include <cmath>

#include "scene/scene.h"
#include "trace/sampling.h"
#include "trace/surface.h"
#include "trace/texture_lookup.h"

namespace ddish::trace {

namespace {

float luminance(const glm::vec3& c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

// glTF's recommended range window: smooth to zero at `range`, none when range is 0.
float range_window(float range, float distance) {
  if (!(range > 0.0f)) return 1.0f;
  const float r = distance / range;
  return std::clamp(1.0f - r * r * r * r, 0.0f, 1.0f);
}

}  // namespace

float spot_attenuation(const scene::Light& light, const glm::vec3& to_point_dir) {
  const float cos_outer = std::cos(light.outer_cone);
  const float cos_inner = std::cos(light.inner_cone);
  const float scale = 1.0f / std::max(1e-3f, cos_inner - cos_outer);
  const float offset = -cos_outer * scale;
  const float cd = glm::dot(glm::normalize(light.direction), to_point_dir);
  const float a = std::clamp(cd * scale + offset, 0.0f, 1.0f);
  return a * a;
}

bool sample_punctual(const scene::Light& light, const glm::vec3& p, LightSample& out) {
  const glm::vec3 power = light.radiant();
  if (!glm::any(glm::greaterThan(power, glm::vec3(0.0f)))) return false;
  out.pdf = 0.0f;
  if (light.type == scene::LightType::Directional) {
    const float len = glm::length(light.direction);
    if (!(len > 0.0f)) return false;
    out.wi = -light.direction / len;
    out.distance = std::numeric_limits<float>::infinity();
    out.radiance = power;  // the irradiance on a surface facing the light
    return true;
  }
  const glm::vec3 d = light.position - p;
  const float dist2 = glm::dot(d, d);
  if (!(dist2 > 0.0f) || !std::isfinite(dist2)) return false;
  const float dist = std::sqrt(dist2);
  out.wi = d / dist;
  out.distance = dist;
  out.point = light.position;
  out.point_magnitude = coordinate_magnitude(light.position);
  float atten = range_window(light.range, dist) / dist2;
  if (light.type == scene::LightType::Spot) atten *= spot_attenuation(light, -out.wi);
  if (!(atten > 0.0f)) return false;
  out.radiance = power * atten;
  return true;
}

LightSet::LightSet(const scene::Scene& scene, const TextureSet& textures)
    : scene_(&scene), textures_(&textures) {
  punctual_ = scene.lights;
  instance_first_.assign(scene.instances.size(), -1);
  for (std::size_t i = 0; i < scene.instances.size(); ++i) {
    const int m = scene.instances[i].mesh;
    if (m < 0 || static_cast<std::size_t>(m) >= scene.meshes.size()) continue;
    const scene::Mesh& mesh = scene.meshes[static_cast<std::size_t>(m)];
    if (!scene.material_of(mesh).is_emissive() || mesh.triangle_count() == 0) continue;
    instance_first_[i] = static_cast<int>(tris_.size());
    tris_.resize(tris_.size() + mesh.triangle_count());
    place(static_cast<std::size_t>(instance_first_[i]), static_cast<int>(i));
  }
  build_cdf();
}

void LightSet::place(std::size_t first, int instance) {
  const scene::Instance& inst = scene_->instances[static_cast<std::size_t>(instance)];
  const scene::Mesh& mesh = scene_->meshes[static_cast<std::size_t>(inst.mesh)];
  const bool two = scene_->material_of(mesh).double_sided;
  // glTF: a mirroring transform makes clockwise triangles the front faces.
  const float front = glm::determinant(glm::mat3(inst.transform)) < 0.0f ? -1.0f : 1.0f;
  for (std::size_t k = 0; k < mesh.triangle_count(); ++k) {
    const WorldTriangle w = world_triangle(mesh, inst.transform, static_cast<int>(k));
    Triangle& t = tris_[first + k];
    t.p0 = w.p0;
    t.e1 = w.p1 - w.p0;
    t.e2 = w.p2 - w.p0;
    const glm::vec3 c = glm::cross(t.e1, t.e2) * front;
    const float len = glm::length(c);
    t.area = std::isfinite(len) ? 0.5f * len : 0.0f;
    t.n = t.area > 0.0f ? c / len : glm::vec3(0.0f, 0.0f, 1.0f);
    t.magnitude =
        std::max({coordinate_magnitude(w.p0), coordinate_magnitude(w.p1), coordinate_magnitude(w.p2)});
    t.instance = instance;
    t.prim = static_cast<int>(k);
    t.double_sided = two;
  }
}

void LightSet::build_cdf() {
  cdf_.assign(tris_.size() + 1, 0.0);
  for (std::size_t k = 0; k < tris_.size(); ++k) {
    const Triangle& t = tris_[k];
    const scene::Mesh& mesh =
        scene_
            ->meshes[static_cast<std::size_t>(scene_->instances[static_cast<std::size_t>(t.instance)].mesh)];
    // Power ∝ area × luminance (× 2 sides); zero-area triangles get probability 0.
    double power = static_cast<double>(t.area) * luminance(scene_->material_of(mesh).emission());
    if (t.double_sided) power *= 2.0;
    cdf_[k + 1] = cdf_[k] + (std::isfinite(power) && power > 0.0 ? power : 0.0);
  }
  total_power_ = cdf_.back();
}

void LightSet::update(const scene::Scene& scene, std::span<const int> moved) {
  scene_ = &scene;
  punctual_ = scene.lights;
  bool changed = false;
  for (int i : moved) {
    if (i < 0 || static_cast<std::size_t>(i) >= instance_first_.size()) continue;
    const int first = instance_first_[static_cast<std::size_t>(i)];
    if (first < 0) continue;
    place(static_cast<std::size_t>(first), i);
    changed = true;
  }
  if (changed) build_cdf();
}

std::span<const scene::Light> LightSet::punctual() const { return punctual_; }

bool LightSet::sample_emissive(const glm::vec3& p, const glm::vec3& u, LightSample& out) const {
  if (!(total_power_ > 0.0)) return false;
  // Pick a triangle by power: the first CDF entry above u·total.
  const double target = static_cast<double>(u.x) * total_power_;
  auto it = std::upper_bound(cdf_.begin() + 1, cdf_.end(), target);
  if (it == cdf_.end()) --it;
  const auto k = static_cast<std::size_t>(it - cdf_.begin() - 1);
  const Triangle& t = tris_[k];
  const double prob = (cdf_[k + 1] - cdf_[k]) / total_power_;
  if (!(prob > 0.0) || !(t.area > 0.0f)) return false;

  const glm::vec2 b = sample_uniform_triangle({u.y, u.z});  // weights of p0, p1; p2 gets the rest
  const float b1 = 1.0f - b.x - b.y;                        // weight of p2 in Embree terms: v
  const glm::vec3 x = t.p0 + t.e1 * b.y + t.e2 * b1;
  const glm::vec3 d = x - p;
  const float dist2 = glm::dot(d, d);
  if (!(dist2 > 0.0f) || !std::isfinite(dist2)) return false;
  const float dist = std::sqrt(dist2);
  const glm::vec3 wi = d / dist;
  const float cos_l = -glm::dot(t.n, wi);  // > 0: p sees the front
  if (cos_l <= 0.0f && !t.double_sided) return false;
  const float abs_cos = std::abs(cos_l);
  if (!(abs_cos > 1e-7f)) return false;

  const scene::Instance& inst = scene_->instances[static_cast<std::size_t>(t.instance)];
  const scene::Mesh& mesh = scene_->meshes[static_cast<std::size_t>(inst.mesh)];
  const scene::Material& mat = scene_->material_of(mesh);
  glm::vec3 le = mat.emission();
  if (const MipTexture* tex = textures_->get(mat.emissive_texture.texture)) {
    // Light samples have no ray cone: the emissive texture is read at its finest level.
    const glm::vec2 uv = slot_uv(mesh, mat.emissive_texture, t.prim, glm::vec3(b.x, b.y, b1));
    le *= glm::vec3(tex->sample(uv, 0.0f, true, wrap_of(mat.emissive_texture)));
  }
  out.wi = wi;
  out.distance = dist;
  out.point = x;
  out.normal = cos_l > 0.0f ? t.n : -t.n;
  out.point_magnitude = t.magnitude;
  out.radiance = le;
  out.pdf = static_cast<float>(prob) / t.area * dist2 / abs_cos;
  return std::isfinite(out.pdf) && out.pdf > 0.0f;
}

float LightSet::emissive_pdf(int instance, int prim, float distance, float cos_light) const {
  if (instance < 0 || static_cast<std::size_t>(instance) >= instance_first_.size()) return 0.0f;
  const int first = instance_first_[static_cast<std::size_t>(instance)];
  if (first < 0 || !(total_power_ > 0.0)) return 0.0f;
  const auto k = static_cast<std::size_t>(first + prim);
  if (k >= tris_.size() || !(tris_[k].area > 0.0f) || !(cos_light > 0.0f)) return 0.0f;
  const double prob = (cdf_[k + 1] - cdf_[k]) / total_power_;
  return static_cast<float>(prob) / tris_[k].area * distance * distance / cos_light;
}

}  // namespace ddish::trace
