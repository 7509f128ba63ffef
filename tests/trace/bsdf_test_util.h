// Helpers of the BSDF tests: directions, albedo by sampling and by quadrature, and a
// chi-square test of sample() against pdf() over bins centred on the mirror direction.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <numbers>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "trace/bsdf.h"
#include "trace/frame.h"
#include "trace/ggx.h"
#include "trace/sampler.h"
#include "trace/sampling.h"
#include "trace/specular_albedo.h"


namespace ddish::trace::bsdf_test {


inline glm::vec3 direction(float cos_theta, float phi = 0.0f) {
  const float s = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
  return {s * std::cos(phi), s * std::sin(phi), cos_theta};
}

inline bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

inline float max_channel(const glm::dvec3& v) { return float(std::max({v.x, v.y, v.z})); }

// Directional albedo integral f(wo, wi) cos(theta_i) dwi estimated with the BSDF's own sampling:
// the mean sample weight (a lost sample counts as 0), and the standard error of that mean.
struct Albedo {
  glm::dvec3 mean{0.0};
  double std_error = 0.0;  // of the largest channel
};

inline Albedo sampled_albedo(const Bsdf& bsdf, const glm::vec3& wo, int n, std::uint64_t stream) {
  Sampler sampler(2024, stream);
  glm::dvec3 sum(0.0);
  glm::dvec3 sum2(0.0);
  for (int i = 0; i < n; ++i) {
    const glm::vec3 u(sampler.next1d(), sampler.next1d(), sampler.next1d());
    BsdfSample s;
    if (bsdf.sample(wo, u, s)) {
      sum += glm::dvec3(s.weight);
      sum2 += glm::dvec3(s.weight) * glm::dvec3(s.weight);
    }
  }
  Albedo a;
  a.mean = sum / double(n);
  const glm::dvec3 var = sum2 / double(n) - a.mean * a.mean;
  a.std_error = std::sqrt(std::max({var.x, var.y, var.z, 0.0}) / double(n));
  return a;
}

// The same integral by a midpoint rule in (cos theta, phi), which never calls sample() or pdf():
// an independent check of the sampling weights, accurate for lobes that are not too narrow.
inline glm::dvec3 quadrature_albedo(const Bsdf& bsdf, const glm::vec3& wo, int n_cos, int n_phi) {
  glm::dvec3 sum(0.0);
  const double cell = (1.0 / n_cos) * (2.0 * std::numbers::pi / n_phi);
  for (int i = 0; i < n_cos; ++i) {
    const float mu = (float(i) + 0.5f) / float(n_cos);
    for (int j = 0; j < n_phi; ++j) {
      const glm::vec3 wi = direction(mu, 2.0f * kPi * (float(j) + 0.5f) / float(n_phi));
      sum += glm::dvec3(bsdf.eval(wo, wi)) * double(mu) * cell;
    }
  }
  return sum;
}

// ---------------------------------------------------------------------------------------------
// Chi-square machinery. The sphere is binned in (theta', phi') about the mirror direction of wo,
// with theta' spaced logarithmically from the lobe's width alpha out to pi: a plain (theta, phi)
// grid about the normal would put the whole lobe of roughness 0.05 (alpha = 0.0025) into one bin
// and test nothing of its shape. Bin probabilities integrate pdf() over each bin with a sub-grid.

class LobeBinning {
 public:
  static constexpr int kTheta = 16;
  static constexpr int kPhi = 24;

  LobeBinning(const glm::vec3& wo, float alpha)
      : frame_(Frame::from_normal(glm::vec3(-wo.x, -wo.y, wo.z))),
        eps_(alpha),
        log_range_(std::log1p(kPi / alpha)) {}

  int bins() const { return kTheta * kPhi; }

  int bin(const glm::vec3& w) const {
    const glm::vec3 l = frame_.to_local(w);
    // atan2, not acos: acos(z) cannot resolve angles below ~3e-4 rad, where z rounds to 1.
    const float theta = std::atan2(std::sqrt(l.x * l.x + l.y * l.y), l.z);
    float phi = std::atan2(l.y, l.x);
    if (phi < 0.0f) {
      phi += 2.0f * kPi;
    }
    const int i = std::min(int(std::log1p(theta / eps_) / log_range_ * kTheta), kTheta - 1);
    const int j = std::min(int(phi / (2.0f * kPi) * kPhi), kPhi - 1);
    return i * kPhi + j;
  }

  // Integral of density(w) over every bin, by a q x q midpoint rule in (g, phi') per bin where
  // theta' = eps (exp(g L) - 1) and dw = sin(theta') L (theta' + eps) dg dphi'.
  template <class Density>
  std::vector<double> integrate(const Density& density, int q) const {
    std::vector<double> mass(bins(), 0.0);
    const double dg = 1.0 / (kTheta * q);
    const double dphi = 2.0 * std::numbers::pi / (kPhi * q);
    for (int i = 0; i < kTheta * q; ++i) {
      const double g = (i + 0.5) * dg;
      const double theta = eps_ * std::expm1(g * log_range_);
      const double jacobian = std::sin(theta) * log_range_ * (theta + eps_);
      for (int j = 0; j < kPhi * q; ++j) {
        const double phi = (j + 0.5) * dphi;
        const glm::vec3 l(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)),
                          float(std::cos(theta)));
        mass[(i / q) * kPhi + j / q] += double(density(frame_.to_world(l))) * jacobian * dg * dphi;
      }
    }
    return mass;
  }

 private:
  Frame frame_;
  float eps_;
  float log_range_;
};

// Regularised upper incomplete gamma Q(a, x): the chi-square survival function is Q(dof/2, chi2/2).
// Power series for P = 1 - Q below x = a + 1, Legendre's continued fraction (modified Lentz) above.
inline double gamma_q(double a, double x) {
  if (x <= 0.0) {
    return 1.0;
  }
  const double log_prefix = -x + a * std::log(x) - std::lgamma(a);
  if (x < a + 1.0) {
    double term = 1.0 / a;
    double sum = term;
    for (int n = 1; n < 10000 && term > sum * 1e-16; ++n) {
      term *= x / (a + n);
      sum += term;
    }
    return std::max(0.0, 1.0 - sum * std::exp(log_prefix));
  }
  constexpr double kTiny = 1e-300;
  double b = x + 1.0 - a;
  double c = 1.0 / kTiny;
  double d = 1.0 / b;
  double h = d;
  for (int i = 1; i < 10000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    d = std::abs(d) < kTiny ? kTiny : d;
    c = b + an / c;
    c = std::abs(c) < kTiny ? kTiny : c;
    d = 1.0 / d;
    const double step = d * c;
    h *= step;
    if (std::abs(step - 1.0) < 1e-15) {
      break;
    }
  }
  return std::exp(log_prefix) * h;
}

struct ChiSquare {
  double statistic = 0.0;
  int dof = 0;
  double p_value = 0.0;
  int samples_where_pdf_is_zero = 0;  // produced directions to which pdf() gives no density
  double pdf_mass = 0.0;      // integral of pdf() over the sphere
  double sample_success = 0;  // fraction of sample() calls that produced a direction
};

// Pearson's test of the histogram of sample() against pdf(). The cell "no direction produced"
// expects N (1 - integral of pdf), so the totals agree and lost samples are tested too. Cells
// expecting fewer than 5 samples are pooled (the chi-square approximation needs about 5 each).
inline ChiSquare chi_square(const Bsdf& bsdf, const glm::vec3& wo, int n, std::uint64_t stream) {
  const LobeBinning binning(wo, Ggx::alpha_from_roughness(bsdf.params().roughness));
  std::vector<double> observed(binning.bins() + 1, 0.0);
  Sampler sampler(99, stream);
  ChiSquare r;
  int produced = 0;
  for (int i = 0; i < n; ++i) {
    const glm::vec3 u(sampler.next1d(), sampler.next1d(), sampler.next1d());
    BsdfSample s;
    if (bsdf.sample(wo, u, s)) {
      ++observed[binning.bin(s.wi)];
      ++produced;
      if (!(bsdf.pdf(wo, s.wi) > 0.0f)) {
        ++r.samples_where_pdf_is_zero;
      }
    } else {
      ++observed.back();
    }
  }
  std::vector<double> mass = binning.integrate([&](const glm::vec3& wi) { return bsdf.pdf(wo, wi); }, 24);
  for (double m : mass) {
    r.pdf_mass += m;
  }
  r.sample_success = double(produced) / n;
  mass.push_back(std::max(0.0, 1.0 - r.pdf_mass));

  std::vector<std::pair<double, double>> cells;  // (expected, observed)
  double pooled_expected = 0.0;
  double pooled_observed = 0.0;
  for (std::size_t i = 0; i < mass.size(); ++i) {
    const double expected = mass[i] * n;
    if (expected < 5.0) {
      pooled_expected += expected;
      pooled_observed += observed[i];
    } else {
      cells.emplace_back(expected, observed[i]);
    }
  }
  if (pooled_expected >= 5.0) {
    cells.emplace_back(pooled_expected, pooled_observed);
  } else if (!cells.empty()) {
    auto smallest = std::min_element(cells.begin(), cells.end());
    smallest->first += pooled_expected;
    smallest->second += pooled_observed;
  }
  for (const auto& [expected, obs] : cells) {
    r.statistic += (obs - expected) * (obs - expected) / expected;
  }
  r.dof = int(cells.size()) - 1;
  r.p_value = gamma_q(0.5 * r.dof, 0.5 * r.statistic);
  return r;
}

struct Case {
  float roughness;
  float metallic;
  glm::vec3 base;
  float cos_o;
};

// ---------------------------------------------------------------------------------------------

}  // namespace ddish::trace::bsdf_test
