// The glTF metallic-roughness BSDF: energy (white furnace), reciprocity, sampling that follows the
// reported pdf (chi-square), sample weights, and finite values at the extremes of its parameters.
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

namespace ddish::trace {
namespace {

glm::vec3 direction(float cos_theta, float phi = 0.0f) {
  const float s = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
  return {s * std::cos(phi), s * std::sin(phi), cos_theta};
}

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

float max_channel(const glm::dvec3& v) { return float(std::max({v.x, v.y, v.z})); }

// Directional albedo integral f(wo, wi) cos(theta_i) dwi estimated with the BSDF's own sampling:
// the mean sample weight (a lost sample counts as 0), and the standard error of that mean.
struct Albedo {
  glm::dvec3 mean{0.0};
  double std_error = 0.0;  // of the largest channel
};

Albedo sampled_albedo(const Bsdf& bsdf, const glm::vec3& wo, int n, std::uint64_t stream) {
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
glm::dvec3 quadrature_albedo(const Bsdf& bsdf, const glm::vec3& wo, int n_cos, int n_phi) {
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
double gamma_q(double a, double x) {
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
ChiSquare chi_square(const Bsdf& bsdf, const glm::vec3& wo, int n, std::uint64_t stream) {
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

TEST(ChiSquareHelper, SurvivalFunctionMatchesKnownQuantiles) {
  // chi2 quantiles: P(X > 6.635 | 1 dof) = 0.01, P(X > 18.307 | 10) = 0.05, P(X > 135.807 | 100) = 0.01.
  EXPECT_NEAR(gamma_q(0.5, 6.635 / 2), 0.01, 1e-4);
  EXPECT_NEAR(gamma_q(5.0, 18.307 / 2), 0.05, 1e-4);
  EXPECT_NEAR(gamma_q(50.0, 135.807 / 2), 0.01, 1e-4);
  EXPECT_NEAR(gamma_q(3.0, 0.5), 0.98561, 1e-4);
}

TEST(SpecularAlbedo, TableMatchesQuadratureAndKnownLimits) {
  const auto& table = DielectricSpecularAlbedo::get();
  double worst = 0.0;
  for (float r : {0.0f, 0.03f, 0.05f, 0.12f, 0.3f, 0.55f, 0.8f, 1.0f}) {
    for (float mu : {1e-4f, 0.003f, 0.02f, 0.07f, 0.2f, 0.45f, 0.8f, 1.0f}) {
      const double reference = DielectricSpecularAlbedo::integrate(mu, r, 128);
      const double error = std::abs(reference - table.directional(mu, r));
      worst = std::max(worst, error);
      EXPECT_LT(error, mu > 0.1f ? 1e-3 : 8e-3) << "mu " << mu << " roughness " << r;
    }
  }
  std::cout << "[ figures  ] specular albedo table: worst error " << worst << "\n";
  // A smooth layer at normal incidence reflects F0; the average lies between F0 and 1.
  EXPECT_NEAR(table.directional(1.0f, 0.0f), DielectricSpecularAlbedo::kF0, 1e-3f);
  for (float r : {0.0f, 0.5f, 1.0f}) {
    EXPECT_GT(table.average(r), 0.0f);
    EXPECT_LT(table.average(r), 0.2f);
  }
}

// GGX itself: D is normalised (integral of D(h) cos(theta_h) = 1), Smith's masking is consistent
// with D (the visible normals of every view integrate to 1: G1(wo) integral max(0, wo.h) D(h) dh
// = wo.z), and G2 is the height-correlated form 1 / (1 + Lambda(wo) + Lambda(wi)), computed here
// from tan(theta) in double precision.
TEST(Ggx, DistributionAndMaskingAreConsistent) {
  const auto lambda = [](double alpha, const glm::vec3& w) {
    const double tan2 = (double(w.x) * w.x + double(w.y) * w.y) / (double(w.z) * w.z);
    return 0.5 * (std::sqrt(1.0 + alpha * alpha * tan2) - 1.0);
  };
  for (float alpha : {0.01f, 0.1f, 0.5f, 1.0f}) {
    const Ggx ggx(alpha);
    const int n_theta = 4000;
    const int n_phi = 128;
    const double d_theta = 0.5 * std::numbers::pi / n_theta;
    const double d_phi = 2.0 * std::numbers::pi / n_phi;
    const std::vector<glm::vec3> views = {direction(1.0f), direction(0.5f, 0.3f), direction(0.1f, 2.0f)};
    double d_norm = 0.0;
    std::vector<double> visible(views.size(), 0.0);
    for (int i = 0; i < n_theta; ++i) {
      const float theta = float((i + 0.5) * d_theta);
      for (int j = 0; j < n_phi; ++j) {
        const glm::vec3 h = direction(std::cos(theta), float((j + 0.5) * d_phi));
        const double dw = std::sin(theta) * d_theta * d_phi;
        d_norm += ggx.d(h) * h.z * dw;
        for (std::size_t v = 0; v < views.size(); ++v) {
          visible[v] += ggx.g1(views[v]) * std::max(0.0f, glm::dot(views[v], h)) * ggx.d(h) / views[v].z * dw;
        }
      }
    }
    EXPECT_NEAR(d_norm, 1.0, 2e-3) << "alpha " << alpha;
    for (std::size_t v = 0; v < views.size(); ++v) {
      EXPECT_NEAR(visible[v], 1.0, 2e-3) << "alpha " << alpha << " view " << v;
    }
    Sampler sampler(4, 4);
    for (int i = 0; i < 200; ++i) {
      const glm::vec3 wo = sample_uniform_hemisphere(sampler.next2d());
      const glm::vec3 wi = sample_uniform_hemisphere(sampler.next2d());
      if (wo.z < 1e-3f || wi.z < 1e-3f) {
        continue;
      }
      const double g2 = 1.0 / (1.0 + lambda(alpha, wo) + lambda(alpha, wi));
      EXPECT_NEAR(ggx.g2(wo, wi), g2, 1e-5 * g2);
      EXPECT_NEAR(ggx.g1(wo), 1.0 / (1.0 + lambda(alpha, wo)), 1e-5);
      EXPECT_NEAR(ggx.visibility(wo, wi), g2 / (4.0 * wo.z * wi.z), 1e-5 * g2 / (4.0 * wo.z * wi.z));
    }
  }
}

// The specular lobe is F D G2 / (4 |n.l| |n.v|) with Schlick's F on F0 = mix(0.04, base, metallic),
// and the diffuse lobe has no specular part: an independent recomputation from the GGX pieces.
TEST(Bsdf, SpecularLobeIsFresnelTimesDTimesG2Over4CosCos) {
  Sampler sampler(12, 1);
  const glm::vec3 base(0.9f, 0.5f, 0.1f);
  for (float roughness : {0.05f, 0.4f, 1.0f}) {
    for (float metallic : {0.0f, 0.3f, 1.0f}) {
      const Bsdf bsdf({base, metallic, roughness});
      const Ggx ggx(Ggx::alpha_from_roughness(roughness));
      const glm::vec3 f0 = glm::mix(glm::vec3(0.04f), base, metallic);
      for (int i = 0; i < 500; ++i) {
        const glm::vec3 wo = sample_uniform_hemisphere(sampler.next2d());
        const glm::vec3 wi = sample_uniform_hemisphere(sampler.next2d());
        if (wo.z < 1e-3f || wi.z < 1e-3f) {
          continue;
        }
        const glm::vec3 h = glm::normalize(wo + wi);
        const glm::vec3 fresnel = f0 + (1.0f - f0) * std::pow(1.0f - glm::dot(wo, h), 5.0f);
        const glm::vec3 expected = fresnel * ggx.d(h) * ggx.g2(wo, wi) / (4.0f * wo.z * wi.z);
        const glm::vec3 f = bsdf.eval_specular(wo, wi);
        for (int c = 0; c < 3; ++c) {
          EXPECT_NEAR(f[c], expected[c], 1e-4f * expected[c] + 1e-7f);
        }
        EXPECT_EQ(bsdf.eval(wo, wi), bsdf.eval_diffuse(wo, wi) + f);
      }
    }
  }
}

// (a) Energy: for every roughness, metallic, colour and view angle, the directional albedo is at
// most 1. The slack is the specular-albedo table's interpolation error (< 0.005 where it makes
// the BSDF gain energy, see specular_albedo.h) plus four standard errors of the estimate.
TEST(Bsdf, DirectionalAlbedoNeverExceedsOne) {
  double worst = 0.0;
  std::uint64_t stream = 0;
  for (const glm::vec3 base : {glm::vec3(1.0f), glm::vec3(1.0f, 0.5f, 0.1f)}) {
    for (float roughness : {0.0f, 0.05f, 0.25f, 0.5f, 0.75f, 1.0f}) {
      for (float metallic : {0.0f, 0.5f, 1.0f}) {
        for (float cos_o : {1.0f, 0.7f, 0.3f, 0.1f, 0.01f, 1e-4f}) {
          const Bsdf bsdf({base, metallic, roughness});
          const Albedo a = sampled_albedo(bsdf, direction(cos_o, 0.3f), 20000, ++stream);
          worst = std::max(worst, double(max_channel(a.mean)));
          EXPECT_LE(max_channel(a.mean), 1.0 + 0.005 + 4.0 * a.std_error)
              << "roughness " << roughness << " metallic " << metallic << " cos " << cos_o;
        }
      }
    }
  }
  std::cout << "[ figures  ] largest directional albedo over the grid: " << worst << "\n";
}

// (c) "Exactly 1 for white Lambert". glTF's dielectric always carries its F0 = 0.04 specular layer,
// so a pure Lambert surface cannot be made from the parameters. What must hold exactly instead is
// that the diffuse base receives all the energy the layer does not reflect: the diffuse lobe's
// albedo is 1 - E(n.v), checked by quadrature to 1e-4 ...
TEST(Bsdf, DiffuseLobePassesExactlyWhatTheLayerLetsThrough) {
  const auto& table = DielectricSpecularAlbedo::get();
  for (float roughness : {0.0f, 0.05f, 0.3f, 0.7f, 1.0f}) {
    const Bsdf bsdf({glm::vec3(1.0f), 0.0f, roughness});
    for (float cos_o : {1.0f, 0.6f, 0.2f, 0.02f}) {
      const glm::vec3 wo = direction(cos_o);
      // The diffuse lobe depends on wi only through cos(theta_i): one fine rule in cos, 4 azimuths.
      const int n = 40000;
      double sum = 0.0;
      for (int i = 0; i < n; ++i) {
        const float mu = (float(i) + 0.5f) / float(n);
        for (int j = 0; j < 4; ++j) {
          sum += double(bsdf.eval_diffuse(wo, direction(mu, 1.3f * float(j))).y) * mu;
        }
      }
      const double albedo = sum / n / 4.0 * 2.0 * std::numbers::pi;
      EXPECT_NEAR(albedo, 1.0 - table.directional(cos_o, roughness), 1e-4)
          << "roughness " << roughness << " cos " << cos_o;
    }
  }
}

// ... and so a white dielectric reflects all the light at every angle and roughness (within the
// table's error): the white furnace for the whole BSDF.
TEST(Bsdf, WhiteDielectricFurnaceIsOne) {
  double worst = 0.0;
  std::uint64_t stream = 1000;
  for (float roughness : {0.0f, 0.05f, 0.2f, 0.5f, 1.0f}) {
    for (float cos_o : {1.0f, 0.7f, 0.3f, 0.1f, 0.01f, 1e-4f}) {
      const Bsdf bsdf({glm::vec3(1.0f), 0.0f, roughness});
      const Albedo a = sampled_albedo(bsdf, direction(cos_o, 1.0f), 40000, ++stream);
      worst = std::max(worst, std::abs(a.mean.x - 1.0));
      EXPECT_NEAR(a.mean.x, 1.0, 0.008 + 4.0 * a.std_error) << "roughness " << roughness << " cos " << cos_o;
    }
  }
  std::cout << "[ figures  ] white dielectric furnace: largest |albedo - 1| = " << worst << "\n";
}

// (b) A white metal is GGX single scattering with F = 1: no energy gain, nearly all energy kept when
// smooth, and a known loss when rough. With alpha = 1 the NDF is constant (1 / pi) and at normal
// incidence the albedo integral reduces to integral of 2 mu / (1 + mu) dmu = 1 - ln 2.
TEST(Bsdf, WhiteMetalMatchesSingleScatteringGgx) {
  const glm::vec3 n(0.0f, 0.0f, 1.0f);
  const Albedo rough = sampled_albedo(Bsdf({glm::vec3(1.0f), 1.0f, 1.0f}), n, 200000, 1);
  std::cout << "[ figures  ] white metal, roughness 1, normal incidence: " << rough.mean.x
            << " (exact 1 - ln 2 = " << 1.0 - std::log(2.0) << ")\n";
  EXPECT_NEAR(rough.mean.x, 1.0 - std::log(2.0), 4.0 * rough.std_error + 1e-4);

  for (float roughness : {0.0f, 0.05f}) {
    for (float cos_o : {1.0f, 0.7f, 0.3f}) {
      const Albedo a = sampled_albedo(Bsdf({glm::vec3(1.0f), 1.0f, roughness}), direction(cos_o), 20000, 7);
      EXPECT_GT(a.mean.x, 0.99) << "roughness " << roughness << " cos " << cos_o;
      EXPECT_LT(a.mean.x, 1.0 + 4.0 * a.std_error + 1e-6);
    }
  }
  // Sampled estimates agree with a quadrature that uses eval() only; energy falls with roughness.
  for (float cos_o : {1.0f, 0.5f, 0.2f}) {
    double previous = 2.0;
    for (float roughness : {0.3f, 0.5f, 0.75f, 1.0f}) {
      const Bsdf bsdf({glm::vec3(1.0f), 1.0f, roughness});
      const Albedo a = sampled_albedo(bsdf, direction(cos_o), 40000, 11);
      const glm::dvec3 q = quadrature_albedo(bsdf, direction(cos_o), 400, 400);
      EXPECT_NEAR(a.mean.x, q.x, 4.0 * a.std_error + 2e-3) << "roughness " << roughness << " cos " << cos_o;
      if (cos_o == 1.0f) {
        EXPECT_LT(q.x, previous);
        previous = q.x;
      }
    }
  }
}

TEST(Bsdf, IsReciprocal) {
  Sampler sampler(5, 6);
  int checked = 0;
  for (float roughness : {0.0f, 0.05f, 0.3f, 1.0f}) {
    for (float metallic : {0.0f, 0.4f, 1.0f}) {
      const Bsdf bsdf({glm::vec3(0.8f, 0.4f, 0.2f), metallic, roughness});
      for (int i = 0; i < 2000; ++i) {
        const glm::vec3 a = sample_uniform_hemisphere(sampler.next2d());
        // Half of the pairs near the mirror configuration, where the lobe is largest.
        glm::vec3 b = sample_uniform_hemisphere(sampler.next2d());
        if (i % 2 == 0) {
          b = glm::normalize(glm::vec3(-a.x, -a.y, a.z) + 0.01f * (b - glm::vec3(0.0f, 0.0f, 0.5f)));
        }
        if (a.z <= 0.0f || b.z <= 0.0f) {
          continue;
        }
        const glm::vec3 fab = bsdf.eval(a, b);
        const glm::vec3 fba = bsdf.eval(b, a);
        for (int c = 0; c < 3; ++c) {
          EXPECT_LE(std::abs(fab[c] - fba[c]), 1e-5f * std::max(std::abs(fab[c]), std::abs(fba[c])) + 1e-30f);
        }
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 20000);
}

// Sampled directions follow pdf(): Pearson chi-square between the histogram of sample() and pdf()
// integrated over the same bins, for narrow (0.05, and the clamped 0) and wide (1) lobes, metals,
// dielectrics, and views from normal to grazing.
TEST(Bsdf, SampledDirectionsFollowPdf) {
  const std::vector<Case> cases = {
      {0.05f, 0.0f, glm::vec3(0.5f), 0.8f},  {0.05f, 1.0f, glm::vec3(0.9f, 0.6f, 0.3f), 0.5f},
      {0.05f, 0.0f, glm::vec3(1.0f), 0.2f},  {0.0f, 1.0f, glm::vec3(1.0f), 0.7f},
      {0.3f, 0.5f, glm::vec3(0.7f), 0.9f},   {0.5f, 0.0f, glm::vec3(0.2f, 0.8f, 0.4f), 0.4f},
      {1.0f, 0.0f, glm::vec3(1.0f), 0.3f},   {1.0f, 1.0f, glm::vec3(1.0f), 1.0f},
      {1.0f, 1.0f, glm::vec3(0.6f), 0.15f},
  };
  std::uint64_t stream = 0;
  for (const Case& c : cases) {
    const Bsdf bsdf({c.base, c.metallic, c.roughness});
    const ChiSquare r = chi_square(bsdf, direction(c.cos_o, 0.7f), 200000, ++stream);
    std::cout << "[ figures  ] chi-square roughness " << c.roughness << " metallic " << c.metallic << " cos "
              << c.cos_o << ": chi2 " << r.statistic << " dof " << r.dof << " p " << r.p_value << " (pdf mass "
              << r.pdf_mass << ", produced " << r.sample_success << ")\n";
    EXPECT_EQ(r.samples_where_pdf_is_zero, 0);
    EXPECT_GT(r.dof, 20) << "too few cells for a meaningful test";
    EXPECT_GT(r.p_value, 0.01) << "roughness " << c.roughness << " metallic " << c.metallic << " cos " << c.cos_o;
  }
}

// pdf() integrates to at most 1 over the sphere, to 1 where no microfacet reflection can fall under
// the horizon, and to the fraction of sample() calls that produce a direction.
TEST(Bsdf, PdfIntegratesToTheProducedFraction) {
  const std::vector<Case> cases = {
      {0.05f, 1.0f, glm::vec3(1.0f), 1.0f}, {0.0f, 0.0f, glm::vec3(0.5f), 0.9f},
      {0.5f, 1.0f, glm::vec3(1.0f), 0.6f},  {1.0f, 1.0f, glm::vec3(1.0f), 1.0f},
      {1.0f, 0.0f, glm::vec3(0.3f), 0.1f},
  };
  std::uint64_t stream = 100;
  for (const Case& c : cases) {
    const Bsdf bsdf({c.base, c.metallic, c.roughness});
    const glm::vec3 wo = direction(c.cos_o, 2.0f);
    const LobeBinning binning(wo, Ggx::alpha_from_roughness(c.roughness));
    double mass = 0.0;
    for (double m : binning.integrate([&](const glm::vec3& wi) { return bsdf.pdf(wo, wi); }, 24)) {
      mass += m;
    }
    const int n = 100000;
    Sampler sampler(3, ++stream);
    int produced = 0;
    for (int i = 0; i < n; ++i) {
      BsdfSample s;
      produced += bsdf.sample(wo, {sampler.next1d(), sampler.next1d(), sampler.next1d()}, s) ? 1 : 0;
    }
    const double fraction = double(produced) / n;
    const double sigma = std::sqrt(std::max(fraction * (1.0 - fraction), 1e-6) / n);
    EXPECT_LE(mass, 1.0 + 2e-3);
    EXPECT_NEAR(mass, fraction, 4.0 * sigma + 2e-3) << "roughness " << c.roughness << " cos " << c.cos_o;
    if (c.roughness <= 0.05f) {
      EXPECT_NEAR(mass, 1.0, 2e-3) << "a near-mirror lobe loses nothing under the horizon";
    }
  }
  // The rough metal at normal incidence: D = 1 / pi, so exactly half of the reflections fall
  // under the horizon (those with theta_h > 45 degrees).
  const Bsdf rough_metal({glm::vec3(1.0f), 1.0f, 1.0f});
  const LobeBinning binning(glm::vec3(0.0f, 0.0f, 1.0f), 1.0f);
  double mass = 0.0;
  for (double m : binning.integrate([&](const glm::vec3& wi) { return rough_metal.pdf({0, 0, 1}, wi); }, 24)) {
    mass += m;
  }
  EXPECT_NEAR(mass, 0.5, 2e-3);
}

TEST(Bsdf, SampleWeightIsEvalCosOverPdf) {
  Sampler sampler(8, 9);
  int produced = 0;
  for (float roughness : {0.0f, 0.05f, 0.3f, 1.0f}) {
    for (float metallic : {0.0f, 0.5f, 1.0f}) {
      const Bsdf bsdf({glm::vec3(0.9f, 0.5f, 0.2f), metallic, roughness});
      for (float cos_o : {1.0f, 0.5f, 0.05f}) {
        const glm::vec3 wo = direction(cos_o, 0.4f);
        for (int i = 0; i < 1000; ++i) {
          BsdfSample s;
          if (!bsdf.sample(wo, {sampler.next1d(), sampler.next1d(), sampler.next1d()}, s)) {
            continue;
          }
          ++produced;
          ASSERT_NEAR(glm::length(s.wi), 1.0f, 1e-5f);
          ASSERT_GT(s.wi.z, 0.0f);
          const float pdf = bsdf.pdf(wo, s.wi);
          ASSERT_GT(s.pdf, 0.0f);
          EXPECT_NEAR(s.pdf, pdf, 1e-5f * pdf);
          const glm::vec3 expected = bsdf.eval(wo, s.wi) * s.wi.z / pdf;
          for (int c = 0; c < 3; ++c) {
            ASSERT_TRUE(std::isfinite(s.weight[c]));
            EXPECT_NEAR(s.weight[c], expected[c], 1e-5f * std::abs(expected[c]) + 1e-12f);
          }
        }
      }
    }
  }
  EXPECT_GT(produced, 30000);
}

// Roughness exactly 0 and 1, views and lights at cos 1e-6 and exactly 0, coincident and opposite
// directions, extreme u: nothing may become NaN or infinite, and below-horizon cases are zero.
TEST(Bsdf, FiniteAtTheExtremes) {
  const std::vector<glm::vec3> directions = {
      {0.0f, 0.0f, 1.0f},           direction(1e-6f, 0.0f), direction(1e-6f, kPi), direction(1e-6f, 1.0f),
      {1.0f, 0.0f, 0.0f},           {-1.0f, 0.0f, 0.0f},    {0.0f, 1.0f, 0.0f},    direction(0.5f, 2.0f),
      {0.0f, 0.0f, -1.0f},          direction(-1e-6f, 0.5f),
  };
  const std::vector<glm::vec3> us = {{0.0f, 0.0f, 0.0f}, {0.99999994f, 0.99999994f, 0.99999994f},
                                     {0.5f, 0.5f, 0.5f}, {0.01f, 0.0f, 0.99999994f},
                                     {0.99f, 0.99999994f, 0.0f}};
  for (float roughness : {0.0f, 1.0f}) {
    for (float metallic : {0.0f, 1.0f}) {
      for (const glm::vec3 base : {glm::vec3(0.0f), glm::vec3(1.0f)}) {
        const Bsdf bsdf({base, metallic, roughness});
        for (const glm::vec3& wo : directions) {
          for (const glm::vec3& wi : directions) {
            const glm::vec3 f = bsdf.eval(wo, wi);
            const float pdf = bsdf.pdf(wo, wi);
            ASSERT_TRUE(finite(f)) << "roughness " << roughness << " wo.z " << wo.z << " wi.z " << wi.z;
            ASSERT_TRUE(std::isfinite(pdf));
            EXPECT_GE(std::min({f.x, f.y, f.z}), 0.0f);
            EXPECT_GE(pdf, 0.0f);
            if (wo.z <= 0.0f || wi.z <= 0.0f) {
              EXPECT_EQ(f, glm::vec3(0.0f));
              EXPECT_EQ(pdf, 0.0f);
            }
          }
          for (const glm::vec3& u : us) {
            BsdfSample s;
            const bool ok = bsdf.sample(wo, u, s);
            if (wo.z <= 0.0f) {
              EXPECT_FALSE(ok) << "n.v = " << wo.z << " must produce no sample";
            }
            if (ok) {
              ASSERT_TRUE(finite(s.weight));
              ASSERT_TRUE(finite(s.wi));
              ASSERT_TRUE(std::isfinite(s.pdf));
              EXPECT_GT(s.pdf, 0.0f);
            }
          }
        }
        // Many random samples at a grazing view: weights stay finite.
        Sampler sampler(1, 2);
        for (int i = 0; i < 5000; ++i) {
          BsdfSample s;
          if (bsdf.sample(direction(1e-6f, 0.3f), {sampler.next1d(), sampler.next1d(), sampler.next1d()}, s)) {
            ASSERT_TRUE(finite(s.weight));
            ASSERT_TRUE(std::isfinite(s.pdf));
          }
        }
      }
    }
  }
}

}  // namespace
}  // namespace ddish::trace
