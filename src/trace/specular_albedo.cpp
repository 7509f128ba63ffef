#include "trace/specular_albedo.h"

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

#include "trace/ggx.h"

namespace ddish::trace {

namespace {

// Integrand resolution for the table: the reflected direction crosses the horizon inside the
// domain, so the midpoint rule converges only like 1/n there; 64 x 64 keeps the error ~1e-3.
constexpr int kQuadrature = 64;

// The table's roughness coordinate: uniform in log(alpha) from kMinAlpha (0) to 1 (1).
float roughness_coordinate(float roughness) {
  return 1.0f - std::log(Ggx::alpha_from_roughness(roughness)) / std::log(Ggx::kMinAlpha);
}

// Position of v in a uniform grid of `nodes` nodes over [0, 1]: the lower node and the fraction.
void locate(float v, int nodes, int& i, float& t) {
  const float f = std::clamp(v, 0.0f, 1.0f) * float(nodes - 1);
  i = std::min(int(f), nodes - 2);
  t = f - float(i);
}

}  // namespace

double DielectricSpecularAlbedo::integrate(float cos_theta, float roughness, int n) {
  // E does not vanish at grazing (G2 / G1(wo) -> 1 as wo grazes), but wo.z = 0 itself has no
  // visible normals to sample: the limit is taken at mu = 1e-6, where E is within 2e-4 of it.
  const float mu = std::clamp(cos_theta, 1e-6f, 1.0f);
  const Ggx ggx(Ggx::alpha_from_roughness(roughness));
  const glm::vec3 wo(std::sqrt(1.0f - mu * mu), 0.0f, mu);
  const float g1 = ggx.g1(wo);
  double sum = 0.0;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const glm::vec2 u((float(i) + 0.5f) / float(n), (float(j) + 0.5f) / float(n));
      const glm::vec3 h = ggx.sample_visible_normal(wo, u);
      const float wo_h = glm::dot(wo, h);
      const glm::vec3 wi = 2.0f * wo_h * h - wo;
      if (wi.z <= 0.0f) {
        continue;
      }
      // f cos / pdf for visible-normal sampling reduces to F * G2 / G1(wo).
      const float fresnel = kF0 + (1.0f - kF0) * std::pow(1.0f - std::clamp(wo_h, 0.0f, 1.0f), 5.0f);
      sum += double(fresnel * ggx.g2(wo, wi) / g1);
    }
  }
  return sum / (double(n) * double(n));
}

DielectricSpecularAlbedo::DielectricSpecularAlbedo() {
  for (int r = 0; r < kRoughnessNodes; ++r) {
    const float y = float(r) / float(kRoughnessNodes - 1);
    const float roughness = std::sqrt(std::pow(Ggx::kMinAlpha, 1.0f - y));  // alpha = kMinAlpha^(1 - y)
    for (int c = 0; c < kCosNodes; ++c) {
      const float x = float(c) / float(kCosNodes - 1);
      e_[r * kCosNodes + c] = float(integrate(x * x * x, roughness, kQuadrature));
    }
    // Exact integral of the piecewise-linear (in x) E against 2 mu dmu = 6 x^5 dx.
    double avg = 0.0;
    for (int c = 0; c + 1 < kCosNodes; ++c) {
      const double x0 = double(c) / double(kCosNodes - 1);
      const double x1 = double(c + 1) / double(kCosNodes - 1);
      const double e0 = e_[r * kCosNodes + c];
      const double e1 = e_[r * kCosNodes + c + 1];
      const double slope = (e1 - e0) / (x1 - x0);
      const double intercept = e0 - slope * x0;
      avg += intercept * (std::pow(x1, 6) - std::pow(x0, 6)) +
             slope * (6.0 / 7.0) * (std::pow(x1, 7) - std::pow(x0, 7));
    }
    e_avg_[r] = float(avg);
  }
}

const DielectricSpecularAlbedo& DielectricSpecularAlbedo::get() {
  static const DielectricSpecularAlbedo table;
  return table;
}

DielectricSpecularAlbedo::Slice DielectricSpecularAlbedo::slice(float roughness) const {
  int r;
  Slice slice;
  locate(roughness_coordinate(roughness), kRoughnessNodes, r, slice.t_);
  slice.row0_ = &e_[r * kCosNodes];
  slice.row1_ = &e_[(r + 1) * kCosNodes];
  return slice;
}

float DielectricSpecularAlbedo::Slice::operator()(float cos_theta) const {
  int c;
  float tc;
  locate(std::cbrt(std::clamp(cos_theta, 0.0f, 1.0f)), kCosNodes, c, tc);
  const float e0 = row0_[c] + tc * (row0_[c + 1] - row0_[c]);
  const float e1 = row1_[c] + tc * (row1_[c + 1] - row1_[c]);
  return e0 + t_ * (e1 - e0);
}

float DielectricSpecularAlbedo::directional(float cos_theta, float roughness) const {
  return slice(roughness)(cos_theta);
}

float DielectricSpecularAlbedo::average(float roughness) const {
  int r;
  float tr;
  locate(roughness_coordinate(roughness), kRoughnessNodes, r, tr);
  return e_avg_[r] + tr * (e_avg_[r + 1] - e_avg_[r]);
}

}  // namespace ddish::trace
