// The isotropic GGX (Trowbridge-Reitz) microfacet distribution in the local shading frame
// (z = macro normal): the normal distribution D, Smith masking (separable G1 and the
// height-correlated G2 in its "visibility" form V = G2 / (4 |n.l| |n.v|)), and sampling of the
// distribution of visible normals with its density. Every formula is written so that it stays
// finite for grazing directions (n.v -> 0) and for the smallest alpha allowed (kMinAlpha).
#pragma once

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

#include "trace/sampling.h"

namespace ddish::trace {

class Ggx {
 public:
  // The smallest alpha used. alpha = 0 is a delta lobe, for which D(h) is 0/0 (NaN) at h = n and
  // 0 elsewhere, so alpha must be clamped; the floor is set by fp32. A direction made by sample()
  // and fed back to pdf() or eval() carries a rounding error of ~1e-7 rad, which changes D by a
  // relative ~4e-7 / alpha, and D's peak 1 / (pi alpha^2) grows fast (3e11 at alpha = 1e-6, 1e23
  // once squared by the power heuristic). At 1e-3 (perceptual roughness 0.032, which looks like a
  // mirror) the round-trip error stays below 0.1 %, D peaks at 3e5, and sampling still passes the
  // chi-square test (tests/trace/bsdf_test.cpp).
  static constexpr float kMinAlpha = 1e-3f;

  // glTF's perceptual roughness r in [0, 1] becomes alpha = r^2, clamped to kMinAlpha.
  static float alpha_from_roughness(float roughness) {
    const float r = std::clamp(roughness, 0.0f, 1.0f);
    return std::max(r * r, kMinAlpha);
  }

  explicit Ggx(float alpha) : alpha_(std::clamp(alpha, kMinAlpha, 1.0f)), alpha2_(alpha_ * alpha_) {}

  float alpha() const { return alpha_; }

  // D(h) for a unit microfacet normal h; 0 below the surface. Written with sin^2 = x^2 + y^2
  // instead of 1 - cos^2, which would lose all precision near the peak when alpha is small.
  float d(const glm::vec3& h) const {
    if (h.z <= 0.0f) {
      return 0.0f;
    }
    const float t = (h.x * h.x + h.y * h.y) / alpha2_ + h.z * h.z;
    return 1.0f / (kPi * alpha2_ * t * t);
  }

  // sqrt(cos^2 + alpha^2 sin^2) of direction w: Smith's Lambda(w) = (s / |cos| - 1) / 2.
  float smith_s(const glm::vec3& w) const {
    return std::sqrt(w.z * w.z + alpha2_ * std::max(0.0f, w.x * w.x + w.y * w.y));
  }

  // Separable masking G1(w) = 1 / (1 + Lambda(w)) = 2 |cos| / (|cos| + s): 0 at grazing, not 0/0.
  float g1(const glm::vec3& w) const {
    const float c = std::abs(w.z);
    const float denom = c + smith_s(w);
    return denom > 0.0f ? 2.0f * c / denom : 0.0f;
  }

  // Height-correlated masking-shadowing G2 = 1 / (1 + Lambda(wo) + Lambda(wi)).
  float g2(const glm::vec3& wo, const glm::vec3& wi) const {
    const float co = std::abs(wo.z);
    const float ci = std::abs(wi.z);
    const float denom = smith_s(wo) * ci + smith_s(wi) * co;
    return denom > 0.0f ? 2.0f * co * ci / denom : 0.0f;
  }

  // V = G2 / (4 |cos_o| |cos_i|) = 1 / (2 (s_o |cos_i| + s_i |cos_o|)): the specular BRDF is
  // F * D * V. The cancelled form has no 1 / cos, so it is finite wherever either cosine is > 0.
  float visibility(const glm::vec3& wo, const glm::vec3& wi) const {
    const float denom = 2.0f * (smith_s(wo) * std::abs(wi.z) + smith_s(wi) * std::abs(wo.z));
    return denom > 0.0f ? 1.0f / denom : 0.0f;
  }

  // Samples a microfacet normal from the distribution of normals visible from wo (wo.z > 0),
  // D_wo(h) = G1(wo) max(0, wo.h) D(h) / wo.z, by the spherical-cap construction of Dupuy and
  // Benyoub (2023), which is equivalent to Heitz (2018) with fewer operations: in the space where
  // the distribution is the unit hemisphere, visible normals are uniform on a spherical cap.
  glm::vec3 sample_visible_normal(const glm::vec3& wo, const glm::vec2& u) const {
    const glm::vec3 v = glm::normalize(glm::vec3(alpha_ * wo.x, alpha_ * wo.y, wo.z));
    const float phi = 2.0f * kPi * u.x;
    const float z = (1.0f - u.y) * (1.0f + v.z) - v.z;
    const float sin_theta = std::sqrt(std::clamp(1.0f - z * z, 0.0f, 1.0f));
    const glm::vec3 c(sin_theta * std::cos(phi), sin_theta * std::sin(phi), z);
    const glm::vec3 hs = c + v;  // hs.z = z + v.z >= 0 by construction
    const glm::vec3 h(alpha_ * hs.x, alpha_ * hs.y, std::max(hs.z, 0.0f));
    const float len2 = glm::dot(h, h);
    return len2 > 1e-30f ? h / std::sqrt(len2) : glm::vec3(0.0f, 0.0f, 1.0f);
  }

  // Solid-angle density of wi = reflect(wo about h) when h comes from sample_visible_normal:
  // D_wo(h) / (4 wo.h) = G1(wo) D(h) / (4 wo.z) = D(h) / (2 (wo.z + s_o)).
  float reflected_pdf(const glm::vec3& wo, const glm::vec3& h) const {
    if (wo.z <= 0.0f) {
      return 0.0f;
    }
    return d(h) / (2.0f * (wo.z + smith_s(wo)));
  }

 private:
  float alpha_;
  float alpha2_;
};

}  // namespace ddish::trace
