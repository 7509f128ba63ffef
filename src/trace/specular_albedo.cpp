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

// The cosine-weighted average of a piecewise-linear (in x = cbrt(mu)) row, exactly: the
// integral against 2 mu dmu = 6 x^5 dx.
float row_average(const float* row, int nodes) {
  double avg = 0.0;
  for (int c = 0; c + 1 < nodes; ++c) {
    const double x0 = double(c) / double(nodes - 1);
    const double x1 = double(c + 1) / double(nodes - 1);
    const double e0 = row[c];
    const double e1 = row[c + 1];
    const double slope = (e1 - e0) / (x1 - x0);
    const double intercept = e0 - slope * x0;
    avg += intercept * (std::pow(x1, 6) - std::pow(x0, 6)) +
           slope * (6.0 / 7.0) * (std::pow(x1, 7) - std::pow(x0, 7));
  }
  return float(avg);
}

float lerp_row(const float* row, int c, float tc) { return row[c] + tc * (row[c + 1] - row[c]); }

}  // namespace

double DielectricSpecularAlbedo::integrate(float cos_theta, float roughness, int n) {
  return integrate_f0(cos_theta, roughness, n, kF0);
}

double DielectricSpecularAlbedo::integrate_f0(float cos_theta, float roughness, int n, float f0) {
  const glm::dvec2 parts = integrate_parts(cos_theta, roughness, n);
  return parts.x + double(f0) * parts.y;
}

glm::dvec2 DielectricSpecularAlbedo::integrate_parts(float cos_theta, float roughness, int n) {
  // E does not vanish at grazing (G2 / G1(wo) -> 1 as wo grazes), but wo.z = 0 itself has no
  // visible normals to sample: the limit is taken at mu = 1e-6, where E is within 2e-4 of it.
  const float mu = std::clamp(cos_theta, 1e-6f, 1.0f);
  const Ggx ggx(Ggx::alpha_from_roughness(roughness));
  const glm::vec3 wo(std::sqrt(1.0f - mu * mu), 0.0f, mu);
  const float g1 = ggx.g1(wo);
  glm::dvec2 sum(0.0);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const glm::vec2 u((float(i) + 0.5f) / float(n), (float(j) + 0.5f) / float(n));
      const glm::vec3 h = ggx.sample_visible_normal(wo, u);
      const float wo_h = glm::dot(wo, h);
      const glm::vec3 wi = 2.0f * wo_h * h - wo;
      if (wi.z <= 0.0f) {
        continue;
      }
      // f cos / pdf for visible-normal sampling reduces to F * G2 / G1(wo), and Schlick's
      // F = w + F0 (1 - w) with w = (1 - wo.h)^5.
      const double g = double(ggx.g2(wo, wi) / g1);
      const double w = std::pow(1.0 - double(std::clamp(wo_h, 0.0f, 1.0f)), 5.0);
      sum += glm::dvec2(w * g, (1.0 - w) * g);
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
      const float mu = x * x * x;
      const glm::dvec2 parts = integrate_parts(mu, roughness, kQuadrature);
      e_[r * kCosNodes + c] = float(parts.x + double(kF0) * parts.y);
      s_[r * kCosNodes + c] = float(parts.y);  // E is linear in F0: this is its slope
    }
    e_avg_[r] = row_average(&e_[r * kCosNodes], kCosNodes);
    s_avg_[r] = row_average(&s_[r * kCosNodes], kCosNodes);
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
  slice.slope0_ = &s_[r * kCosNodes];
  slice.slope1_ = &s_[(r + 1) * kCosNodes];
  return slice;
}

DielectricSpecularAlbedo::AtRoughness DielectricSpecularAlbedo::at(float roughness) const {
  int r;
  AtRoughness a;
  locate(roughness_coordinate(roughness), kRoughnessNodes, r, a.slice.t_);
  const float tr = a.slice.t_;
  a.slice.row0_ = &e_[r * kCosNodes];
  a.slice.row1_ = &e_[(r + 1) * kCosNodes];
  a.slice.slope0_ = &s_[r * kCosNodes];
  a.slice.slope1_ = &s_[(r + 1) * kCosNodes];
  a.average = e_avg_[r] + tr * (e_avg_[r + 1] - e_avg_[r]);
  a.average_slope = s_avg_[r] + tr * (s_avg_[r + 1] - s_avg_[r]);
  return a;
}

float DielectricSpecularAlbedo::Slice::operator()(float cos_theta) const {
  int c;
  float tc;
  locate(std::cbrt(std::clamp(cos_theta, 0.0f, 1.0f)), kCosNodes, c, tc);
  const float e0 = lerp_row(row0_, c, tc);
  const float e1 = lerp_row(row1_, c, tc);
  return e0 + t_ * (e1 - e0);
}

float DielectricSpecularAlbedo::Slice::slope(float cos_theta) const {
  int c;
  float tc;
  locate(std::cbrt(std::clamp(cos_theta, 0.0f, 1.0f)), kCosNodes, c, tc);
  const float s0 = lerp_row(slope0_, c, tc);
  const float s1 = lerp_row(slope1_, c, tc);
  return s0 + t_ * (s1 - s0);
}

glm::vec2 DielectricSpecularAlbedo::Slice::with_slope(float cos_theta) const {
  int c;
  float tc;
  locate(std::cbrt(std::clamp(cos_theta, 0.0f, 1.0f)), kCosNodes, c, tc);
  const float e0 = lerp_row(row0_, c, tc);
  const float e1 = lerp_row(row1_, c, tc);
  const float s0 = lerp_row(slope0_, c, tc);
  const float s1 = lerp_row(slope1_, c, tc);
  return {e0 + t_ * (e1 - e0), s0 + t_ * (s1 - s0)};
}

float DielectricSpecularAlbedo::directional(float cos_theta, float roughness) const {
  return slice(roughness)(cos_theta);
}

float DielectricSpecularAlbedo::directional_slope(float cos_theta, float roughness) const {
  return slice(roughness).slope(cos_theta);
}

float DielectricSpecularAlbedo::average(float roughness) const {
  int r;
  float tr;
  locate(roughness_coordinate(roughness), kRoughnessNodes, r, tr);
  return e_avg_[r] + tr * (e_avg_[r + 1] - e_avg_[r]);
}

float DielectricSpecularAlbedo::average_slope(float roughness) const {
  int r;
  float tr;
  locate(roughness_coordinate(roughness), kRoughnessNodes, r, tr);
  return s_avg_[r] + tr * (s_avg_[r + 1] - s_avg_[r]);
}

}  // namespace ddish::trace
