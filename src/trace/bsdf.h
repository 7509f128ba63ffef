// The glTF 2.0 metallic-roughness BSDF: Lambert diffuse plus GGX specular with height-correlated
// Smith masking-shadowing and Schlick Fresnel, mixed for metals and dielectrics as the glTF
// specification's appendix B describes, except that the diffuse base is coupled to the specular
// layer by albedo scaling so that energy is conserved (bsdf.cpp explains). All directions are in
// the local shading frame (z = the shading normal), both pointing away from the surface.
#pragma once

#include <glm/glm.hpp>

#include "trace/specular_albedo.h"

namespace ddish::trace {

struct BsdfParams {
  glm::vec3 base_color{1.0f};
  float metallic = 0.0f;
  float roughness = 1.0f;  // glTF perceptual roughness; GGX alpha = roughness^2 (clamped: Ggx::kMinAlpha)
  // The dielectric layer (KHR_materials_ior / KHR_materials_specular): its normal reflectance
  // (0.04: ior 1.5) and its weight.
  glm::vec3 dielectric_f0{0.04f};
  float specular = 1.0f;
};

struct BsdfSample {
  glm::vec3 wi{0.0f};      // sampled incident direction (local frame)
  glm::vec3 weight{0.0f};  // f(wo, wi) * |cos theta_i| / pdf
  float pdf = 0.0f;        // solid-angle density of wi
};

class Bsdf {
 public:
  explicit Bsdf(const BsdfParams& params);
  // The same BSDF with the dielectric layer's albedo toward `wo` computed once: the integrator
  // evaluates, samples and weighs one wo per hit several times (the same numbers as without).
  Bsdf(const BsdfParams& params, const glm::vec3& wo);

  // f(wo, wi) without the cosine factor; zero when either direction is below the surface.
  glm::vec3 eval(const glm::vec3& wo, const glm::vec3& wi) const;
  // Solid-angle density with which sample() produces wi.
  float pdf(const glm::vec3& wo, const glm::vec3& wi) const;
  // Samples wi from u in [0,1)^3 (u.x chooses the lobe); returns false when no direction was
  // produced (wo below the surface, or a sample under the horizon).
  bool sample(const glm::vec3& wo, const glm::vec3& u, BsdfSample& out) const;

  const BsdfParams& params() const { return params_; }

  // The two lobes of eval() separately (f without the cosine; eval is their sum): the
  // diffuse base and the specular microfacet lobe. For tests and for debugging views.
  glm::vec3 eval_diffuse(const glm::vec3& wo, const glm::vec3& wi) const;
  glm::vec3 eval_specular(const glm::vec3& wo, const glm::vec3& wi) const;
  // Probability with which sample() picks the specular lobe for this wo.
  float specular_probability(const glm::vec3& wo) const;

 private:
  // pdf() for wi and wo above the surface, with the lobe choice already known.
  float mixture_pdf(const glm::vec3& wo, const glm::vec3& wi, float p_specular) const;

  // The dielectric layer's albedo per channel: specular * (E(mu) + (F0 - 0.04) S(mu)); the
  // stored value when cos_theta is the constructor's wo.z.
  glm::vec3 layer(float cos_theta) const;
  glm::vec3 layer_of(float cos_theta) const;

  BsdfParams params_;
  float alpha_;
  // The specular lobe's Fresnel, f0_ + f90_minus_f0_ (1 - v.h)^5: the dielectric layer's
  // Schlick term weighted by (1 - metallic) specular, plus the metal's weighted by metallic.
  glm::vec3 f0_{0.04f};
  glm::vec3 f90_minus_f0_{0.96f};
  glm::vec3 diffuse_{0.0f};   // (1 - metallic) base / (pi (1 - E_avg)), see bsdf.cpp
  float diffuse_weight_ = 0;  // (1 - metallic) * mean(base): the diffuse lobe's share estimate
  DielectricSpecularAlbedo::Slice layer_albedo_;  // E(mu) of the dielectric layer at this roughness
  float wo_cos_ = -2.0f;          // the wo.z whose layer albedo is stored (-2: none)
  glm::vec3 wo_layer_{0.0f};
};

}  // namespace ddish::trace
