// The glTF metallic-roughness BSDF.
//
// f = (1 - metallic) * dielectric + metallic * metal, with
//   metal      = F(base_color, v.h) * D * V
//   dielectric = s F(F0d, v.h) * D * V  +  base_color / pi * coupling(wo, wi)
// D is GGX with alpha = roughness^2 (clamped to Ggx::kMinAlpha), V the height-correlated Smith
// visibility G2 / (4 |n.l| |n.v|), F Schlick's Fresnel. The dielectric layer's F0d is 0.04 (ior
// 1.5) unless KHR_materials_ior / KHR_materials_specular change it (((ior - 1) / (ior + 1))^2
// times the specular colour), and s is KHR_materials_specular's weight (1 by default). The two
// specular terms merge into one Schlick-like term A + B (1 - v.h)^5, since F is linear in F0:
// A = (1 - metallic) s F0d + metallic base, B = (1 - metallic) s (1 - F0d) + metallic (1 - base);
// with the defaults this is Schlick with F0 = mix(0.04, base_color, metallic).
//
// One deliberate departure from appendix B: the diffuse base is weighted by the albedo-scaling
// coupling of Kelemen and Szirmay-Kalos (2001),
//   coupling = (1 - E(n.v)) (1 - E(n.l)) / (1 - E_avg),
// where E is the directional albedo of the specular layer (DielectricSpecularAlbedo; for another
// F0d and weight s, s (E + (F0d - 0.04) dE/dF0) per channel, exact since E is linear in F0), instead of
// appendix B's fresnel_mix weight 1 - F(v.h). The latter is not energy-conserving: its diffuse
// part keeps 0.93-0.96 of the light at every view angle while the layer above reflects up to F(n.v)
// -> 1, so a white dielectric reflects 1.03 of the incident light at 60 degrees and 1.84 at
// grazing angles (measured). The coupling gives the base exactly the energy the layer lets through,
// so a white dielectric reflects exactly 1 at every angle and roughness, is reciprocal (symmetric
// in v and l), and differs from appendix B by a few per cent away from grazing angles.
//
// Sampling picks the specular lobe (visible normals, then reflection) with probability p_s and the
// diffuse lobe (cosine-weighted) otherwise; p_s estimates the specular share of the reflected
// energy for this wo. pdf() is the one-sample mixture p_s pdf_s + (1 - p_s) pdf_d, and the weight is
// f cos / pdf with that mixture, so the estimator stays unbiased whichever lobe made the sample and
// a lobe sampled with small probability cannot produce a large weight.
#include "trace/bsdf.h"

#include <algorithm>
#include <cmath>

#include "trace/cpu_dispatch.h"
#include "trace/ggx.h"
#include "trace/sampling.h"
#include "trace/specular_albedo.h"

namespace ddish::trace {

namespace {

float mean(const glm::vec3& v) { return (v.x + v.y + v.z) * (1.0f / 3.0f); }

// Schlick's (1 - cos)^5; cos is clamped so that rounding past 1 cannot make it negative.
float schlick_weight(float cos_theta) {
  const float m = 1.0f - std::clamp(cos_theta, 0.0f, 1.0f);
  const float m2 = m * m;
  return m2 * m2 * m;
}

}  // namespace

Bsdf::Bsdf(const BsdfParams& params) : params_(params), alpha_(Ggx::alpha_from_roughness(params.roughness)) {
  params_.base_color = glm::clamp(params.base_color, glm::vec3(0.0f), glm::vec3(1.0f));
  params_.metallic = std::clamp(params.metallic, 0.0f, 1.0f);
  params_.roughness = std::clamp(params.roughness, 0.0f, 1.0f);
  params_.dielectric_f0 = glm::clamp(params.dielectric_f0, glm::vec3(0.0f), glm::vec3(1.0f));
  params_.specular = std::clamp(params.specular, 0.0f, 1.0f);
  const float dielectric = 1.0f - params_.metallic;
  const float m = params_.metallic;
  const float s = params_.specular;
  f0_ = dielectric * s * params_.dielectric_f0 + m * params_.base_color;
  f90_minus_f0_ = dielectric * s * (1.0f - params_.dielectric_f0) + m * (1.0f - params_.base_color);
  const DielectricSpecularAlbedo::AtRoughness rows = DielectricSpecularAlbedo::get().at(params_.roughness);
  layer_albedo_ = rows.slice;
  // The layer's cosine-weighted average albedo, per channel (linear in F0 as E is).
  const glm::vec3 e_avg =
      s * (rows.average + (params_.dielectric_f0 - DielectricSpecularAlbedo::kF0) * rows.average_slope);
  diffuse_ = dielectric * params_.base_color * kInvPi / (1.0f - e_avg);
  diffuse_weight_ = dielectric * mean(params_.base_color);
}

Bsdf::Bsdf(const BsdfParams& params, const glm::vec3& wo) : Bsdf(params) {
  wo_layer_ = layer_of(wo.z);
  wo_cos_ = wo.z;
}

glm::vec3 Bsdf::layer(float cos_theta) const {
  return cos_theta == wo_cos_ ? wo_layer_ : layer_of(cos_theta);
}

glm::vec3 Bsdf::layer_of(float cos_theta) const {
  const glm::vec3 df0 = params_.dielectric_f0 - DielectricSpecularAlbedo::kF0;
  const glm::vec2 es = layer_albedo_.with_slope(cos_theta);
  return params_.specular * (es.x + df0 * es.y);
}

glm::vec3 Bsdf::eval_diffuse(const glm::vec3& wo, const glm::vec3& wi) const {
  if (wo.z <= 0.0f || wi.z <= 0.0f) {
    return glm::vec3(0.0f);
  }
  return diffuse_ * (1.0f - layer(wo.z)) * (1.0f - layer(wi.z));
}

glm::vec3 Bsdf::eval_specular(const glm::vec3& wo, const glm::vec3& wi) const {
  if (wo.z <= 0.0f || wi.z <= 0.0f) {
    return glm::vec3(0.0f);
  }
  const Ggx ggx(alpha_);
  const glm::vec3 h = glm::normalize(wo + wi);  // both above the surface: the sum is not zero
  // wo.h and wi.h are equal but round differently; their mean keeps eval exactly reciprocal.
  const float cos_h = 0.5f * (glm::dot(wo, h) + glm::dot(wi, h));
  const glm::vec3 fresnel = f0_ + f90_minus_f0_ * schlick_weight(cos_h);
  return fresnel * (ggx.d(h) * ggx.visibility(wo, wi));
}

DDISH_CPU_DISPATCH
glm::vec3 Bsdf::eval(const glm::vec3& wo, const glm::vec3& wi) const {
  return eval_diffuse(wo, wi) + eval_specular(wo, wi);
}

float Bsdf::specular_probability(const glm::vec3& wo) const {
  const float e = mean(layer(wo.z));
  const glm::vec3 metal_fresnel = params_.base_color + (1.0f - params_.base_color) * schlick_weight(wo.z);
  const float specular = (1.0f - params_.metallic) * e + params_.metallic * mean(metal_fresnel);
  const float diffuse = diffuse_weight_ * (1.0f - e);
  const float total = specular + diffuse;
  return total > 0.0f ? specular / total : 1.0f;
}

float Bsdf::pdf(const glm::vec3& wo, const glm::vec3& wi) const {
  if (wo.z <= 0.0f || wi.z <= 0.0f) {
    return 0.0f;
  }
  return mixture_pdf(wo, wi, specular_probability(wo));
}

DDISH_CPU_DISPATCH
float Bsdf::mixture_pdf(const glm::vec3& wo, const glm::vec3& wi, float p_specular) const {
  const glm::vec3 h = glm::normalize(wo + wi);
  const float pdf_specular = Ggx(alpha_).reflected_pdf(wo, h);
  return p_specular * pdf_specular + (1.0f - p_specular) * cosine_hemisphere_pdf(wi.z);
}

DDISH_CPU_DISPATCH
bool Bsdf::sample(const glm::vec3& wo, const glm::vec3& u, BsdfSample& out) const {
  if (wo.z <= 0.0f) {
    return false;
  }
  const float p_specular = specular_probability(wo);
  glm::vec3 wi;
  if (u.x < p_specular) {
    const glm::vec3 h = Ggx(alpha_).sample_visible_normal(wo, {u.y, u.z});
    wi = 2.0f * glm::dot(wo, h) * h - wo;
  } else {
    wi = sample_cosine_hemisphere({u.y, u.z});
  }
  if (wi.z <= 0.0f) {
    return false;  // a microfacet reflection under the horizon (or a cosine sample on it)
  }
  wi = glm::normalize(wi);
  const float density = mixture_pdf(wo, wi, p_specular);
  if (!(density > 0.0f)) {
    return false;
  }
  out.wi = wi;
  out.pdf = density;
  out.weight = eval(wo, wi) * (wi.z / density);
  return true;
}

}  // namespace ddish::trace
