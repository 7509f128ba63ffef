// The directional albedo E(mu) of glTF's dielectric specular layer (GGX, height-correlated Smith
// G2, Schlick Fresnel with F0 = 0.04): the fraction of light arriving from a direction with
// cos(theta) = mu that the layer reflects, and its cosine-weighted average E_avg. The BSDF uses it
// to couple the diffuse base to the layer energy-conservingly (see bsdf.cpp); a rasterizer can
// use the same numbers as a lookup texture so that both renderers shade alike.
#pragma once

#include <array>

#include <glm/glm.hpp>

namespace ddish::trace {

class DielectricSpecularAlbedo {
 public:
  static constexpr float kF0 = 0.04f;  // glTF's dielectric: ior 1.5
  static constexpr int kCosNodes = 32;
  static constexpr int kRoughnessNodes = 32;

  // The shared table, computed by quadrature on first use (thread-safe, ~tens of ms).
  static const DielectricSpecularAlbedo& get();

  // E(mu) at one roughness: the two table rows around it, kept for repeated lookups (a BSDF
  // holds one). Valid as long as the table, i.e. for the whole program.
  // Schlick's Fresnel is linear in F0, so the albedo of a layer of any F0 (KHR_materials_ior,
  // KHR_materials_specular) is E(mu) + (F0 - kF0) * S(mu), with S(mu) = dE/dF0 the integral of
  // (1 - (1 - wo.h)^5) G2 / G1 (the second table); slope() reads it.
  class Slice {
   public:
    float operator()(float cos_theta) const;
    float slope(float cos_theta) const;
    // Both at once, {E, S}: one cube root and one node search for the two (the BSDF's case).
    glm::vec2 with_slope(float cos_theta) const;

   private:
    friend class DielectricSpecularAlbedo;
    const float* row0_ = nullptr;
    const float* row1_ = nullptr;
    const float* slope0_ = nullptr;
    const float* slope1_ = nullptr;
    float t_ = 0.0f;
  };
  Slice slice(float roughness) const;
  // slice(), average() and average_slope() of one roughness from one node search (a BSDF's
  // construction, at every hit).
  struct AtRoughness {
    Slice slice;
    float average = 0.0f;
    float average_slope = 0.0f;
  };
  AtRoughness at(float roughness) const;

  // E(mu, roughness), bilinear in (cbrt(mu), log(alpha)); both are clamped to [0, 1]. Its error
  // against integrate() is below 0.007 everywhere (worst near mu = 0.003, roughness 0.05; where
  // the table is below the truth, so that the BSDF gains energy, below 0.005) and below 0.001
  // for mu > 0.1.
  float directional(float cos_theta, float roughness) const;
  // E_avg(roughness) = integral of E(mu) 2 mu dmu over [0, 1] of the same interpolant, so that
  // integral (1 - E(mu)) 2 mu dmu = 1 - E_avg holds exactly for the table's E.
  float average(float roughness) const;
  // S(mu, roughness) = dE/dF0 and its cosine-weighted average, interpolated as E is.
  float directional_slope(float cos_theta, float roughness) const;
  float average_slope(float roughness) const;

  // E(mu, roughness) by direct quadrature over visible normals (n x n stratified midpoints); the
  // table's source, and the tests' reference.
  static double integrate(float cos_theta, float roughness, int n);
  // The same for a layer of normal reflectance f0 (integrate() is f0 = kF0).
  static double integrate_f0(float cos_theta, float roughness, int n, float f0);
  // Both parts of E = parts.x + F0 * parts.y: the integrals of w G2 / G1 and (1 - w) G2 / G1,
  // w = (1 - wo.h)^5.
  static glm::dvec2 integrate_parts(float cos_theta, float roughness, int n);

 private:
  DielectricSpecularAlbedo();

  // Nodes are uniform in x = cbrt(mu) and in log(alpha) from Ggx::kMinAlpha to 1: at grazing
  // angles E depends on about alpha / mu, which changes fastest where both are small, so the
  // nodes crowd there.
  std::array<float, kCosNodes * kRoughnessNodes> e_{};
  std::array<float, kRoughnessNodes> e_avg_{};
  std::array<float, kCosNodes * kRoughnessNodes> s_{};  // dE/dF0
  std::array<float, kRoughnessNodes> s_avg_{};
};

}  // namespace ddish::trace
