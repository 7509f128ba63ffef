// The glTF BSDF's sampling: directions follow the reported pdf (chi-square), the pdf integrates
// to the fraction of directions produced, and sample weights equal eval * cos / pdf.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "bsdf_test_util.h"
#include "trace/bsdf.h"
#include "trace/frame.h"
#include "trace/ggx.h"
#include "trace/sampler.h"
#include "trace/sampling.h"
#include "trace/specular_albedo.h"

namespace ddish::trace {
namespace {

using namespace bsdf_test;

TEST(ChiSquareHelper, SurvivalFunctionMatchesKnownQuantiles) {
  // chi2 quantiles: P(X > 6.635 | 1 dof) = 0.01, P(X > 18.307 | 10) = 0.05, P(X > 135.807 | 100) = 0.01.
  EXPECT_NEAR(gamma_q(0.5, 6.635 / 2), 0.01, 1e-4);
  EXPECT_NEAR(gamma_q(5.0, 18.307 / 2), 0.05, 1e-4);
  EXPECT_NEAR(gamma_q(50.0, 135.807 / 2), 0.01, 1e-4);
  EXPECT_NEAR(gamma_q(3.0, 0.5), 0.98561, 1e-4);
}

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

}  // namespace
}  // namespace ddish::trace
