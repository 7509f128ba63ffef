// Monte-Carlo projection converges to the analytic coefficients of a constant, a clamped
// cosine and a narrow bright cap, with the error falling as 1/sqrt(N).
#include <cmath>
#include <functional>
#include <random>

#include <gtest/gtest.h>

#include "sh/projection.h"
#include "test_util.h"

namespace ddish::sh {
namespace {

using test::kPi;

struct Case {
  const char* name;
  std::function<glm::vec3(const glm::vec3&)> f;
  ShRgb exact;
};

std::vector<Case> cases() {
  std::vector<Case> out;
  const glm::vec3 rgb(1.0f, 0.5f, 0.25f);
  {
    double z[5] = {4.0 * kPi, 0, 0, 0, 0};  // constant 1: 2 pi * integral of P_0 = 4 pi
    out.push_back({"constant", [rgb](const glm::vec3&) { return rgb; },
                   test::zonal_sh(z, glm::vec3(0, 1, 0), rgb, 4)});
  }
  {
    const glm::vec3 axis = glm::normalize(glm::vec3(0.3f, 0.8f, -0.52f));
    double z[5];
    test::clamped_cosine_factors(z);
    out.push_back({"clamped cosine",
                   [rgb, axis](const glm::vec3& w) { return rgb * std::max(0.0f, glm::dot(w, axis)); },
                   test::zonal_sh(z, axis, rgb, 4)});
  }
  {
    // A cap of 0.25 rad (0.2 % of the sphere) at radiance 1000: a small bright emitter.
    const glm::vec3 axis = glm::normalize(glm::vec3(-0.6f, 0.2f, 0.77f));
    const double c0 = std::cos(0.25);
    const glm::vec3 l = 1000.0f * rgb;
    double z[5];
    test::cap_factors(c0, z);
    out.push_back({"bright cap",
                   [l, axis, c0](const glm::vec3& w) {
                     return double(glm::dot(w, axis)) > c0 ? l : glm::vec3(0.0f);
                   },
                   test::zonal_sh(z, axis, l, 4)});
  }
  return out;
}

ShRgb project_mc(const Case& c, int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  ShProjector p(4);
  const float w = uniform_sphere_weight(std::uint64_t(n));
  for (int k = 0; k < n; ++k) {
    const glm::vec3 d = test::uniform_sphere(rng);
    p.add(d, c.f(d), w);
  }
  return p.result();
}

TEST(ShProjection, ErrorFallsAsInverseSqrtOfSamples) {
  const int n1 = 1024, n2 = 16 * n1, seeds = 64;
  for (const Case& c : cases()) {
    double e1 = 0.0, e2 = 0.0;
    for (int s = 0; s < seeds; ++s) {
      e1 += test::coeff_error(project_mc(c, n1, 1000 + s), c.exact);
      e2 += test::coeff_error(project_mc(c, n2, 5000 + s), c.exact);
    }
    const double ratio = e2 / e1;
    const double scale = test::coeff_error(c.exact, ShRgb(4));
    std::printf("[sh] MC projection %-14s: rel. error %.2e at N=%d, %.2e at N=%d, ratio %.3f\n",
                c.name, e1 / seeds / scale, n1, e2 / seeds / scale, n2, ratio);
    EXPECT_LT(ratio, 0.35) << c.name;  // 1/sqrt(16) = 0.25
    EXPECT_GT(ratio, 0.15) << c.name;  // and not suspiciously fast (e.g. a biased estimator)
  }
}

// At N = 65536 every coefficient is within 4 standard errors (estimated from the samples).
TEST(ShProjection, WithinFourSigmaOfAnalytic) {
  const int n = 65536;
  for (const Case& c : cases()) {
    std::mt19937_64 rng(99);
    std::vector<glm::dvec3> sum(kMaxCoeffs), sum2(kMaxCoeffs);
    ShProjector p(4);
    for (int k = 0; k < n; ++k) {
      const glm::vec3 d = test::uniform_sphere(rng);
      const glm::vec3 v = c.f(d);
      p.add(d, v, uniform_sphere_weight(n));
      double y[kMaxCoeffs];
      eval_basis(glm::dvec3(d), 4, y);
      for (int i = 0; i < kMaxCoeffs; ++i) {
        const glm::dvec3 x = glm::dvec3(v) * (4.0 * kPi * y[i]);
        sum[std::size_t(i)] += x;
        sum2[std::size_t(i)] += x * x;
      }
    }
    const ShRgb est = p.result();
    for (int i = 0; i < kMaxCoeffs; ++i) {
      for (int ch = 0; ch < 3; ++ch) {
        const double mean = sum[std::size_t(i)][ch] / n;
        const double var = std::max(0.0, sum2[std::size_t(i)][ch] / n - mean * mean);
        const double se = std::sqrt(var / n);
        EXPECT_NEAR(est[i][ch], c.exact[i][ch], 4.0 * se + 1e-5 * (1.0 + std::fabs(c.exact[i][ch])))
            << c.name << " coefficient " << i << " channel " << ch;
      }
    }
  }
}

TEST(ShProjection, ConstantIsExactForL0AndNormalizedEstimate) {
  std::mt19937_64 rng(3);
  ShProjector p(2);
  for (int k = 0; k < 100; ++k) p.add(test::uniform_sphere(rng), glm::vec3(2.0f), 0.37f);
  // Self-normalised: exact L0 for a constant whatever the weights' scale.
  EXPECT_NEAR(p.result_normalized()[0].x, 2.0 * 2.0 * std::sqrt(kPi), 1e-5);
  EXPECT_EQ(p.sample_count(), 100u);
  EXPECT_NEAR(p.weight_sum(), 100 * double(0.37f), 1e-9);
}

TEST(ShProjection, MergeEqualsSequential) {
  std::mt19937_64 rng(11);
  ShProjector all(3), a(3), b(3);
  for (int k = 0; k < 200; ++k) {
    const glm::vec3 d = test::uniform_sphere(rng);
    const glm::vec3 v(float(k % 7), 1.0f, 0.5f);
    all.add(d, v, 0.1f);
    (k < 80 ? a : b).add(d, v, 0.1f);
  }
  a.merge(b);
  const ShRgb x = all.result(), y = a.result();
  for (int i = 0; i < x.count(); ++i)
    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(x[i][ch], y[i][ch], 1e-5f);
  a.reset();
  EXPECT_EQ(a.sample_count(), 0u);
  EXPECT_EQ(a.result()[0].x, 0.0f);
}

TEST(ShProjection, DirectionProjectionEvaluatesToDeltaKernel) {
  // project_direction(d, v) evaluated at d is v * sum_i Y_i(d)^2 = v (L+1)^2 / (4 pi).
  const glm::vec3 d = glm::normalize(glm::vec3(0.2f, -0.9f, 0.4f));
  for (int order = 0; order <= 4; ++order) {
    const ShRgb sh = project_direction(d, glm::vec3(1.0f), order);
    EXPECT_NEAR(eval(sh, d).x, coeff_count(order) / (4.0 * kPi), 1e-5) << order;
  }
}

}  // namespace
}  // namespace ddish::sh
