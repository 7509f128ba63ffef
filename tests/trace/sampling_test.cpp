// Warping functions and the shading frame: every warp must produce points in its domain with the
// density it reports, checked by histograms against the analytic bin probabilities.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

#include <glm/glm.hpp>

#include "trace/frame.h"
#include "trace/sampler.h"
#include "trace/sampling.h"

namespace ddish::trace {
namespace {

constexpr int kSamples = 200000;

// Counts samples falling in `bins` equal bins of a statistic with range [lo, hi] and compares each
// count with kSamples * probability(bin); a bin may deviate by 5 binomial standard deviations
// (a wrong density shifts whole bins by many more at this sample count).
void expect_histogram(const std::function<float(Sampler&)>& statistic, float lo, float hi, int bins,
                      const std::function<double(double, double)>& probability) {
  Sampler sampler(7, 3);
  std::vector<int> counts(bins, 0);
  for (int i = 0; i < kSamples; ++i) {
    const float v = statistic(sampler);
    ASSERT_GE(v, lo);
    ASSERT_LE(v, hi);
    const int b = std::min(int((v - lo) / (hi - lo) * float(bins)), bins - 1);
    ++counts[b];
  }
  for (int b = 0; b < bins; ++b) {
    const double a = lo + (hi - lo) * b / bins;
    const double c = lo + (hi - lo) * (b + 1) / bins;
    const double p = probability(a, c);
    const double expected = kSamples * p;
    const double sigma = std::sqrt(kSamples * p * (1.0 - p));
    EXPECT_NEAR(counts[b], expected, 5.0 * sigma + 1.0) << "bin [" << a << ", " << c << ")";
  }
}

float azimuth(const glm::vec3& w) {
  const float phi = std::atan2(w.y, w.x);
  return phi < 0.0f ? phi + 2.0f * kPi : phi;
}

TEST(Sampling, CosineHemisphereFollowsCosineOverPi) {
  // P(cos theta in [a, b]) = b^2 - a^2 for density cos / pi; azimuth uniform.
  expect_histogram([](Sampler& s) { return sample_cosine_hemisphere(s.next2d()).z; }, 0.0f, 1.0f, 20,
                   [](double a, double b) { return b * b - a * a; });
  expect_histogram([](Sampler& s) { return azimuth(sample_cosine_hemisphere(s.next2d())); }, 0.0f,
                   2.0f * kPi, 16, [](double a, double b) { return (b - a) / (2.0 * std::numbers::pi); });
  EXPECT_FLOAT_EQ(cosine_hemisphere_pdf(1.0f), kInvPi);
  EXPECT_FLOAT_EQ(cosine_hemisphere_pdf(-0.5f), 0.0f);
}

TEST(Sampling, UniformHemisphereAndSphere) {
  expect_histogram([](Sampler& s) { return sample_uniform_hemisphere(s.next2d()).z; }, 0.0f, 1.0f, 20,
                   [](double a, double b) { return b - a; });
  expect_histogram([](Sampler& s) { return sample_uniform_sphere(s.next2d()).z; }, -1.0f, 1.0f, 20,
                   [](double a, double b) { return (b - a) / 2.0; });
  expect_histogram([](Sampler& s) { return azimuth(sample_uniform_sphere(s.next2d())); }, 0.0f, 2.0f * kPi, 16,
                   [](double a, double b) { return (b - a) / (2.0 * std::numbers::pi); });
  // The densities integrate to one over their domains.
  EXPECT_NEAR(uniform_hemisphere_pdf() * 2.0f * kPi, 1.0f, 1e-6f);
  EXPECT_NEAR(uniform_sphere_pdf() * 4.0f * kPi, 1.0f, 1e-6f);
}

TEST(Sampling, UniformConeStaysInsideAndIsUniform) {
  const float cos_max = 0.8f;
  expect_histogram([&](Sampler& s) { return sample_uniform_cone(s.next2d(), cos_max).z; }, cos_max, 1.0f, 10,
                   [&](double a, double b) { return (b - a) / (1.0 - cos_max); });
  EXPECT_NEAR(uniform_cone_pdf(cos_max) * 2.0f * kPi * (1.0f - cos_max), 1.0f, 1e-6f);
}

TEST(Sampling, ConcentricDiskIsUniformPerArea) {
  // P(r in [a, b]) = b^2 - a^2 on the unit disk.
  expect_histogram([](Sampler& s) { return glm::length(sample_uniform_disk(s.next2d())); }, 0.0f, 1.0f, 20,
                   [](double a, double b) { return b * b - a * a; });
  expect_histogram(
      [](Sampler& s) {
        const glm::vec2 d = sample_uniform_disk(s.next2d());
        return azimuth({d.x, d.y, 0.0f});
      },
      0.0f, 2.0f * kPi, 16, [](double a, double b) { return (b - a) / (2.0 * std::numbers::pi); });
  EXPECT_EQ(sample_uniform_disk({0.5f, 0.5f}), glm::vec2(0.0f));
}

TEST(Sampling, TriangleBarycentricsAreUniform) {
  // Uniform on a triangle: each barycentric b has P(b <= t) = 1 - (1 - t)^2.
  const auto marginal = [](double a, double b) { return (1.0 - a) * (1.0 - a) - (1.0 - b) * (1.0 - b); };
  expect_histogram([](Sampler& s) { return sample_uniform_triangle(s.next2d()).x; }, 0.0f, 1.0f, 20, marginal);
  expect_histogram([](Sampler& s) { return sample_uniform_triangle(s.next2d()).y; }, 0.0f, 1.0f, 20, marginal);
  expect_histogram(
      [](Sampler& s) {
        const glm::vec2 b = sample_uniform_triangle(s.next2d());
        return 1.0f - b.x - b.y;
      },
      0.0f, 1.0f, 20, marginal);
}

TEST(Frame, IsOrthonormalAndRoundTrips) {
  Sampler sampler(11, 5);
  std::vector<glm::vec3> normals = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {0, -1, 0}};
  // Near -z is where the older Frisvad construction lost all precision.
  normals.push_back(glm::normalize(glm::vec3(1e-4f, -2e-4f, -1.0f)));
  for (int i = 0; i < 1000; ++i) {
    normals.push_back(sample_uniform_sphere(sampler.next2d()));
  }
  for (const glm::vec3& n : normals) {
    const Frame f = Frame::from_normal(n);
    EXPECT_NEAR(glm::length(f.t), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::length(f.b), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(f.t, f.b), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(f.t, n), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(f.b, n), 0.0f, 1e-5f);
    EXPECT_LT(glm::length(glm::cross(f.t, f.b) - n), 1e-5f) << "frame is not right-handed";
    const glm::vec3 v = sample_uniform_sphere(sampler.next2d());
    EXPECT_LT(glm::length(f.to_world(f.to_local(v)) - v), 1e-5f);
    EXPECT_NEAR(f.to_local(n).z, 1.0f, 1e-5f);
  }
}

}  // namespace
}  // namespace ddish::trace
