// Image-based lighting (--environment): the equirectangular map's conventions
// (scene/environment_map.h), its importance sampling (trace/environment_light.h) and the path
// tracer's use of it (trace/tracer.cpp), on synthetic maps whose answers are derived here.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "scene/environment_map.h"
#include "trace/environment_light.h"
#include "trace/sampler.h"
#include "trace_test_scenes.h"

namespace ddish::trace {
namespace {

constexpr double kPi = std::numbers::pi;

using Texel = std::function<glm::vec3(int x, int y)>;

std::shared_ptr<const scene::EnvironmentMap> make_map(int height, const Texel& texel,
                                                      float rotation_deg = 0.0f,
                                                      float intensity = 1.0f) {
  const int width = 2 * height;
  std::vector<glm::vec3> t;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) t.push_back(texel(x, y));
  return std::make_shared<const scene::EnvironmentMap>(
      scene::make_environment_map(width, height, std::move(t), rotation_deg, intensity, "test"));
}

// A map with structure everywhere: a gradient in both directions, a bright band and a dark cap.
glm::vec3 busy_texel(int x, int y) {
  float l = 0.2f + 0.05f * static_cast<float>(x % 7) + 0.02f * static_cast<float>(y);
  if (y >= 5 && y <= 7) l += 20.0f;     // a bright band above the horizon
  if (x >= 40 && x <= 43 && y == 12) l += 300.0f;  // a small sun
  if (y >= 28) l = 0.0f;                // black below
  return {l, 0.5f * l, 0.25f * l};
}

double luminance(const glm::vec3& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

TEST(EnvironmentMap, DirectionsFollowTheDocumentedOrientation) {
  const auto map = make_map(8, [](int, int) { return glm::vec3(1.0f); });
  const auto near = [](glm::vec2 a, glm::vec2 b) { return glm::length(a - b) < 1e-5f; };
  EXPECT_TRUE(near(map->uv_of({0, 0, -1}), {0.5f, 0.5f}));   // the centre is -Z
  EXPECT_TRUE(near(map->uv_of({1, 0, 0}), {0.75f, 0.5f}));   // +X to its right
  EXPECT_TRUE(near(map->uv_of({-1, 0, 0}), {0.25f, 0.5f}));
  EXPECT_NEAR(map->uv_of({0, 1, 0}).y, 0.0f, 1e-6f);         // row 0 is up
  EXPECT_NEAR(map->uv_of({0, -1, 0}).y, 1.0f, 1e-6f);
  for (const glm::vec3 d : {glm::vec3(0.3f, 0.5f, -0.8f), glm::vec3(-0.6f, -0.2f, 0.7f)}) {
    const glm::vec3 n = glm::normalize(d);
    EXPECT_LT(glm::length(map->direction_of(map->uv_of(n)) - n), 1e-5f);
  }
}

TEST(EnvironmentMap, RotationTurnsTheMapCounterClockwiseSeenFromAbove) {
  // A map bright only in the file's +X quarter (u in [0.625, 0.875): azimuths 45 to 135 degrees
  // from -Z toward +X).
  const auto texel = [](int x, int) { return glm::vec3(x >= 40 && x < 56 ? 1.0f : 0.0f); };
  const auto plain = make_map(32, texel);
  const auto turned = make_map(32, texel, 90.0f);
  EXPECT_EQ(plain->radiance({1, 0, 0}), glm::vec3(1.0f));
  EXPECT_EQ(plain->radiance({0, 0, -1}), glm::vec3(0.0f));
  // Turned +90 degrees about +Y: +Z -> +X -> -Z, so the light arrives from -Z.
  EXPECT_EQ(turned->radiance({0, 0, -1}), glm::vec3(1.0f));
  EXPECT_EQ(turned->radiance({1, 0, 0}), glm::vec3(0.0f));
  const EnvironmentLight light(turned);
  Sampler sampler(3, 0);
  for (int i = 0; i < 1000; ++i) {
    EnvironmentSample s;
    ASSERT_TRUE(light.sample(sampler.next2d(), s));
    const double azimuth = std::atan2(s.wi.x, -s.wi.z) * 180.0 / kPi;  // 0 at -Z, 90 at +X
    EXPECT_LE(std::abs(azimuth), 45.0 + 1e-3) << "every sample lies within 45 degrees of -Z";
  }
}

TEST(EnvironmentMap, RefusesMapsThatAreNotTwoToOne) {
  EXPECT_THROW(scene::make_environment_map(10, 10, std::vector<glm::vec3>(100), 0, 1, "sq.exr"),
               std::invalid_argument);
  EXPECT_THROW(scene::make_environment_map(0, 0, {}, 0, 1, "empty.exr"), std::invalid_argument);
  std::vector<glm::vec3> bad(8, glm::vec3(1.0f));
  bad[3].g = -1.0f;
  EXPECT_THROW(scene::make_environment_map(4, 2, bad, 0, 1, "neg.exr"), std::invalid_argument);
}

// The density is normalised over the sphere: the integral of pdf(w) dw, by a midpoint rule in
// (u, v) four times finer than the texels (dw = 2 pi^2 sin(theta) du dv), is 1.
TEST(EnvironmentLight, DensityIntegratesToOne) {
  for (const float rotation : {0.0f, 37.0f}) {
    const EnvironmentLight light(make_map(32, busy_texel, rotation));
    const auto map = make_map(32, busy_texel, rotation);
    const int nu = 256;
    const int nv = 128;
    double sum = 0.0;
    for (int j = 0; j < nv; ++j) {
      const double v = (j + 0.5) / nv;
      for (int i = 0; i < nu; ++i) {
        const double u = (i + 0.5) / nu;
        const glm::vec3 d = map->direction_of({static_cast<float>(u), static_cast<float>(v)});
        sum += light.pdf(d) * 2.0 * kPi * kPi * std::sin(kPi * v) / (nu * nv);
      }
    }
    EXPECT_NEAR(sum, 1.0, 1e-3) << "rotation " << rotation;
  }
}

// Samples land on texel (x, y) with probability luminance * sin(theta_row) / sum (computed here
// from the texels, not from the class): a chi-square test over the texels with at least 5
// expected hits (the rest pooled), at 1e-4 significance via the Wilson-Hilferty normal
// approximation; each sample's pdf equals pdf(wi), and the map's radiance is what it returns.
TEST(EnvironmentLight, SamplesFollowTheLuminanceTimesSinTheta) {
  const auto map = make_map(32, busy_texel);
  const EnvironmentLight light(map);
  const int w = 64;
  const int h = 32;
  std::vector<double> expected(static_cast<std::size_t>(w * h));
  double total = 0.0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double p = luminance(busy_texel(x, y)) * std::sin(kPi * (y + 0.5) / h);
      expected[static_cast<std::size_t>(y * w + x)] = p;
      total += p;
    }
  const int n = 400000;
  std::vector<double> counts(expected.size(), 0.0);
  Sampler sampler(11, 0);
  int pdf_mismatches = 0;
  for (int i = 0; i < n; ++i) {
    EnvironmentSample s;
    ASSERT_TRUE(light.sample(sampler.next2d(), s));
    const glm::vec2 uv = map->uv_of(s.wi);
    const int x = std::min(static_cast<int>(uv.x * w), w - 1);
    const int y = std::min(static_cast<int>(uv.y * h), h - 1);
    counts[static_cast<std::size_t>(y * w + x)] += 1.0;
    // pdf(wi) finds the texel again from the direction; rounding can put a sample on a texel
    // boundary into its neighbour, so a few of them differ.
    if (std::abs(s.pdf - light.pdf(s.wi)) > 1e-4f * s.pdf) ++pdf_mismatches;
    ASSERT_LT(glm::length(s.radiance - map->radiance(s.wi)), 1e-4f);
  }
  EXPECT_LT(pdf_mismatches, n / 1000) << "samples whose pdf differs from pdf(wi)";
  double chi2 = 0.0;
  int dof = -1;
  double pooled_e = 0.0;
  double pooled_c = 0.0;
  for (std::size_t k = 0; k < expected.size(); ++k) {
    const double e = expected[k] / total * n;
    if (e >= 5.0) {
      chi2 += (counts[k] - e) * (counts[k] - e) / e;
      ++dof;
    } else {
      pooled_e += e;
      pooled_c += counts[k];
    }
  }
  if (pooled_e > 0.0) {
    chi2 += (pooled_c - pooled_e) * (pooled_c - pooled_e) / pooled_e;
    ++dof;
  }
  // Wilson-Hilferty: (chi2/k)^(1/3) is normal with mean 1 - 2/(9k), variance 2/(9k).
  const double k = dof;
  const double z = (std::cbrt(chi2 / k) - (1.0 - 2.0 / (9.0 * k))) / std::sqrt(2.0 / (9.0 * k));
  RecordProperty("chi2", std::to_string(chi2));
  std::printf("chi-square %.1f over %d degrees of freedom, z = %.2f\n", chi2, dof, z);
  EXPECT_LT(z, 3.72) << "chi2 " << chi2 << " dof " << dof;  // one-sided 1e-4
  EXPECT_EQ(counts[static_cast<std::size_t>(30 * w + 10)], 0.0) << "black texels are never picked";
}

// Importance-sampled integral of the map's radiance over the sphere, E[L / pdf], for a
// two-hemisphere map (upper 2, lower 0.5): 4 pi (2 + 0.5) / 2 = 5 pi, to within a bilinear
// blur of the horizon row that cancels by symmetry.
TEST(EnvironmentLight, EstimatorOfTheSphereIntegralIsUnbiased) {
  const auto map = make_map(16, [](int, int y) { return glm::vec3(y < 8 ? 2.0f : 0.5f); });
  const EnvironmentLight light(map);
  Sampler sampler(5, 1);
  double sum = 0.0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    EnvironmentSample s;
    ASSERT_TRUE(light.sample(sampler.next2d(), s));
    sum += s.radiance.x / s.pdf;
  }
  EXPECT_NEAR(sum / n, 5.0 * kPi, 0.01 * 5.0 * kPi);
}

// White furnace: the open box of furnace_test.cpp in a constant environment map of radiance 1
// sees 1, as it does in the uniform sky of the same radiance, and the two agree within noise.
TEST(EnvironmentLight, WhiteFurnaceUnderAConstantMapEqualsTheUniformSky) {
  scene::Scene s;
  scene::Material white = testing::diffuse(glm::vec3(1.0f), 0.5f, 0.0f);
  white.double_sided = true;
  testing::add_box_inward(s, {-1, -1, -1}, {1, 1, 1}, testing::add_material(s, white), true);
  PathOptions opt;
  opt.max_bounces = 200;
  const Ray ray{{0.3f, 3.0f, 0.2f}, glm::normalize(glm::vec3(-0.1f, -1.0f, 0.05f))};
  s.sidecar.environment = glm::vec3(1.0f);
  const testing::Estimate sky = testing::estimate(Tracer(s, opt), ray, 20000);
  s.sidecar.environment = glm::vec3(0.0f);
  s.environment_map = make_map(16, [](int, int) { return glm::vec3(1.0f); });
  Tracer tracer(s, opt);
  const testing::Estimate map = testing::estimate(tracer, ray, 20000);
  testing::report("white furnace, constant map", map.mean.x, map.stderr_.x, 1.0);
  EXPECT_NEAR(map.mean.x, 1.0, 4.0 * map.stderr_.x + 5e-3);
  EXPECT_NEAR(map.mean.x, sky.mean.x, 4.0 * std::hypot(map.stderr_.x, sky.stderr_.x));
  EXPECT_EQ(tracer.invalid_paths(), 0u);
}

// A Lambertian floor (no dielectric layer: specular weight 0) facing +Y under a band of
// radiance Lb between elevations a and b, black elsewhere, has irradiance
// E = pi Lb (sin^2 b - sin^2 a), so its radiance is albedo E / pi whichever way it is seen. The
// band is rows 4..7 of a 32-row map (polar angles 22.5 to 45 degrees, elevations 45 to 67.5);
// bilinear lookups blur its edges by half a row either side, so the expected irradiance is the
// integral of the bilinear map (fine quadrature), checked against the closed form to 2 %.
TEST(EnvironmentLight, LambertianFloorUnderABandHasTheAnalyticIrradiance) {
  const int h = 32;
  const float band = 8.0f;
  const auto map = make_map(h, [&](int, int y) { return glm::vec3(y >= 4 && y <= 7 ? band : 0.0f); });
  // Irradiance on +Y of the bilinear map: radiance is a function of theta alone, piecewise
  // linear between row centres; integrate L(theta) cos sin 2 pi d theta by a fine midpoint rule.
  double e = 0.0;
  const int steps = 200000;
  for (int i = 0; i < steps; ++i) {
    const double theta = (i + 0.5) / steps * (kPi / 2.0);
    const glm::vec3 d{static_cast<float>(std::sin(theta)), static_cast<float>(std::cos(theta)), 0.0f};
    e += map->radiance(d).x * std::cos(theta) * std::sin(theta) * 2.0 * kPi * (kPi / 2.0) / steps;
  }
  // The piecewise-constant band alone, for the record: pi Lb (cos^2 22.5 - cos^2 45).
  const double closed = kPi * band * (std::pow(std::cos(kPi / 8.0), 2) - 0.5);
  EXPECT_NEAR(e, closed, 0.02 * closed) << "the bilinear blur moves the band's irradiance little";

  scene::Scene s;
  scene::Material lambert = testing::diffuse(glm::vec3(0.5f), 1.0f, 0.0f);
  lambert.specular = 0.0f;
  testing::add_quad(s, {0, 0, 0}, {0, 0, 50}, {50, 0, 0}, testing::add_material(s, lambert));
  s.environment_map = map;
  PathOptions opt;
  opt.max_bounces = 4;
  Tracer tracer(s, opt);
  const testing::Estimate est =
      testing::estimate(tracer, Ray{{0.0f, 1.0f, 1.0f}, glm::normalize(glm::vec3(0.0f, -1.0f, -0.5f))}, 4000);
  const double expected = 0.5 * e / kPi;
  testing::report("Lambertian floor under a band", est.mean.x, est.stderr_.x, expected);
  // Importance sampling makes this nearly noise-free: the stderr at 4000 paths is ~1e-3.
  EXPECT_NEAR(est.mean.x, expected, 4.0 * est.stderr_.x + 1e-3 * expected);
  EXPECT_LT(est.stderr_.x, 0.01 * expected);
}

}  // namespace
}  // namespace ddish::trace
