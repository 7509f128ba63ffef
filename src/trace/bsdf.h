// The glTF 2.0 metallic-roughness BSDF: Lambert diffuse plus GGX specular with height-correlated
// Smith masking-shadowing and Schlick Fresnel, mixed for metals and dielectrics as the glTF
// specification's appendix B describes. All directions are in the local shading frame (z = the
// shading normal), both pointing away from the surface.
#pragma once

#include <glm/glm.hpp>

namespace ddish::trace {

struct BsdfParams {
  glm::vec3 base_color{1.0f};
  float metallic = 0.0f;
  float roughness = 1.0f;  // glTF perceptual roughness; GGX alpha = roughness^2 (clamped, see .cpp)
};

struct BsdfSample {
  glm::vec3 wi{0.0f};      // sampled incident direction (local frame)
  glm::vec3 weight{0.0f};  // f(wo, wi) * |cos theta_i| / pdf
  float pdf = 0.0f;        // solid-angle density of wi
};

class Bsdf {
 public:
  explicit Bsdf(const BsdfParams& params);

  // f(wo, wi) without the cosine factor; zero when either direction is below the surface.
  glm::vec3 eval(const glm::vec3& wo, const glm::vec3& wi) const;
  // Solid-angle density with which sample() produces wi.
  float pdf(const glm::vec3& wo, const glm::vec3& wi) const;
  // Samples wi from u in [0,1)^3 (u.x chooses the lobe); returns false when no direction was
  // produced (wo below the surface, or a sample under the horizon).
  bool sample(const glm::vec3& wo, const glm::vec3& u, BsdfSample& out) const;

  const BsdfParams& params() const { return params_; }

 private:
  BsdfParams params_;
  float alpha_;
};

}  // namespace ddish::trace
