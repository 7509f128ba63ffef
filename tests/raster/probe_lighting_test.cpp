// probe_irradiance / probe_specular (shaders/include/probe_lighting.glsl) on the GPU against
// the CPU sh module: uniform volumes, trilinear interpolation, inactive probes, SH orders.
#include <gtest/gtest.h>

#include <cstdio>
#include <vector>

#include "probe_lighting_harness.h"
#include "probe_test_util.h"
#include "sh/convolution.h"
#include "sh/ggx_zh.h"

namespace ddish::raster::test {
namespace {

const scene::Aabb kBounds{glm::vec3(-1.0f, 0.0f, -0.5f), glm::vec3(2.0f, 1.5f, 1.0f)};

// The error fp16 storage can cause in sum_l scale_l sum_m c_lm Y_lm(d): every coefficient is
// off by at most 2^-11 of itself (round to nearest), plus float arithmetic.
glm::vec3 fp16_bound(const sh::ShRgb& s, const glm::vec3& d, const sh::BandScales& scale) {
  float y[sh::kMaxCoeffs];
  sh::eval_basis(d, s.order, y);
  glm::vec3 bound(0.0f);
  for (int i = 0; i < s.count(); ++i)
    bound += std::abs(scale[std::size_t(sh::band_of(i))] * y[i]) * glm::abs(s[i]);
  return bound * (1.0f / 2048.0f) * 1.05f + 1e-5f * (1.0f + bound);
}

class ProbeLightingTest : public ProbeGpuTest {};

// (a) and (d): every probe holds the same SH, so interpolation is exact and the GPU must give
// sh::irradiance and sh::ggx_specular anywhere, inside the grid or clamped to it.
TEST_F(ProbeLightingTest, UniformVolumeMatchesCpuAtEveryOrder) {
  for (int order : {1, 2, 3, 4}) {
    SCOPED_TRACE("SH order " + std::to_string(order));
    std::mt19937 rng(17u + unsigned(order));
    probes::ProbeVolume volume(probes::ProbeGrid(kBounds, {4, 3, 2}), order);
    const sh::ShRgb s = random_sh(rng, order, 1.0f, 0.3f, false);
    for (std::uint32_t i = 0; i < volume.probe_count(); ++i) volume.set_sh(i, s);
    ProbeTextures textures(device(), volume);
    textures.upload(runner(), volume);

    std::uniform_real_distribution<float> u(-0.2f, 1.2f);  // beyond the bounds too
    std::vector<Query> queries;
    std::vector<glm::vec3> dirs;
    const float roughness[] = {0.0f, 0.02f, 0.3f, 0.7f, 1.0f};
    for (int q = 0; q < 60; ++q) {
      const glm::vec3 p = kBounds.min + kBounds.extent() * glm::vec3(u(rng), u(rng), u(rng));
      dirs.push_back(random_direction(rng));
      queries.push_back(irradiance_query(p, dirs.back()));
      for (float r : roughness) queries.push_back(specular_query(p, dirs.back(), r));
    }
    // probe_lighting(), both results from one interpolation, at the first 20 points.
    for (int q = 0; q < 20; ++q) {
      const glm::vec3 p(queries[std::size_t(6 * q)].a);
      queries.push_back(lighting_query(Kind::lighting_irradiance, p, dirs[std::size_t(q)], 0.4f));
      queries.push_back(lighting_query(Kind::lighting_specular, p, dirs[std::size_t(q)], 0.4f));
    }
    Harness harness(device(), textures, brdf(), order);
    const auto results = harness.run(runner(), queries);
    float worst = 0.0f;  // largest error as a fraction of the fp16 bound
    for (std::size_t q = 0; q < queries.size(); ++q) {
      const bool separate = q < 6 * dirs.size();
      const glm::vec3 r_dir = separate ? dirs[q / 6] : dirs[(q - 6 * dirs.size()) / 2];
      // Separate calls: irradiance, then specular at each roughness; probe_lighting: both.
      const bool diffuse = separate ? q % 6 == 0 : q % 2 == 0;
      const float rough = separate ? (diffuse ? 0.0f : roughness[q % 6 - 1]) : 0.4f;
      const glm::vec3 d = separate || !diffuse ? r_dir : lighting_normal(r_dir);
      const sh::BandScales scale = diffuse ? sh::kCosineLobe : sh::ggx_zh(rough);
      const glm::vec3 expected = glm::max(
          diffuse ? sh::irradiance(s, d) : sh::ggx_specular(s, d, rough), glm::vec3(0.0f));
      const glm::vec3 bound = fp16_bound(s, d, scale);
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(results[q][c], expected[c], bound[c]) << "query " << q;
        worst = std::max(worst, std::abs(results[q][c] - expected[c]) / bound[c]);
      }
    }
    std::printf("[ uniform L%d ] largest error = %.3f of the fp16 bound\n", order, worst);
  }
}

// (b): probes hold different SH; at every cell midpoint the result is the mean of the 8 corner
// probes' irradiance (the analytic trilinear value), and at random points the trilinear lerp.
TEST_F(ProbeLightingTest, TrilinearInterpolationBetweenProbes) {
  std::mt19937 rng(5u);
  probes::ProbeVolume volume(probes::ProbeGrid(kBounds, {3, 3, 3}), 2);
  for (std::uint32_t i = 0; i < volume.probe_count(); ++i)
    volume.set_sh(i, random_sh(rng, 2, 1.0f, 0.25f, true));
  ProbeTextures textures(device(), volume);
  textures.upload(runner(), volume);

  std::vector<Query> queries;
  std::vector<glm::vec3> expected;
  const probes::ProbeGrid& grid = volume.grid();
  for (int cell = 0; cell < 8; ++cell) {
    const glm::ivec3 c0(cell & 1, (cell >> 1) & 1, (cell >> 2) & 1);
    const glm::vec3 mid = grid.position(c0) + 0.5f * grid.spacing();
    const glm::vec3 n = random_direction(rng);
    glm::vec3 mean(0.0f);
    for (int k = 0; k < 8; ++k) {
      const glm::ivec3 corner = c0 + glm::ivec3(k & 1, (k >> 1) & 1, k >> 2);
      mean += sh::irradiance(volume.sh(grid.index(corner)), n);
    }
    queries.push_back(irradiance_query(mid, n));
    expected.push_back(glm::max(mean / 8.0f, glm::vec3(0.0f)));
  }
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int q = 0; q < 64; ++q) {
    const glm::vec3 p = kBounds.min + kBounds.extent() * glm::vec3(u(rng), u(rng), u(rng));
    const glm::vec3 n = random_direction(rng);
    bool valid = false;
    queries.push_back(irradiance_query(p, n));
    const sh::ShRgb interpolated = cpu_interpolate(volume, p, valid);
    expected.push_back(glm::max(sh::irradiance(interpolated, n), glm::vec3(0.0f)));
  }
  Harness harness(device(), textures, brdf(), 2);
  const auto results = harness.run(runner(), queries);
  float worst_mid = 0.0f, worst_any = 0.0f;
  for (std::size_t q = 0; q < queries.size(); ++q) {
    const float err = max_abs(glm::vec3(results[q]) - expected[q]) / max_abs(expected[q]);
    float& worst = q < 8 ? worst_mid : worst_any;
    worst = std::max(worst, err);
    // Midpoints have weights of exactly 1/2; elsewhere GPUs with 8-bit filter fractions may
    // quantise the weights (lavapipe filters in fp32).
    EXPECT_LT(err, q < 8 ? 1e-5f : 2e-3f) << "query " << q;
  }
  std::printf("[ trilinear ] relative error: midpoints %.2e, random points %.2e\n", worst_mid,
              worst_any);
}

// (c): an inactive probe is weighted out. With every active probe holding the same SH, the
// result equals that SH's irradiance everywhere, next to and on the inactive probe as well; with
// different SH a cell midpoint gives the mean of the 7 active corners; with all 8 inactive, 0.
TEST_F(ProbeLightingTest, InactiveProbesAreWeightedOut) {
  std::mt19937 rng(9u);
  const std::uint32_t centre = 13;  // probe (1, 1, 1) of 3 x 3 x 3
  probes::ProbeVolume same(probes::ProbeGrid(kBounds, {3, 3, 3}), 2);
  const sh::ShRgb s = random_sh(rng, 2, 1.0f, 0.2f, true);
  for (std::uint32_t i = 0; i < same.probe_count(); ++i) same.set_sh(i, s);
  same.deactivate(centre, true);
  probes::ProbeVolume mixed(same.grid(), 2);
  for (std::uint32_t i = 0; i < mixed.probe_count(); ++i)
    mixed.set_sh(i, random_sh(rng, 2, 1.0f, 0.0f, true));
  mixed.deactivate(centre, true);

  const probes::ProbeGrid& grid = same.grid();
  const glm::vec3 p_centre = grid.position(centre);
  const glm::vec3 mid = grid.position(glm::ivec3(0)) + 0.5f * grid.spacing();
  const std::vector<glm::vec3> points = {
      p_centre, p_centre + 0.001f * grid.spacing(), p_centre - 0.3f * grid.spacing(), mid,
      p_centre + glm::vec3(0.5f, -0.2f, 0.1f) * grid.spacing()};
  const glm::vec3 n = glm::normalize(glm::vec3(0.3f, 0.8f, -0.5f));
  std::vector<Query> queries;
  for (const auto& p : points) queries.push_back(irradiance_query(p, n));

  {
    ProbeTextures textures(device(), same);
    textures.upload(runner(), same);
    const auto results = Harness(device(), textures, brdf(), 2).run(runner(), queries);
    const glm::vec3 expected = sh::irradiance(s, n);
    for (std::size_t q = 0; q < points.size(); ++q)
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(results[q][c], expected[c], 1e-5f * expected[c]) << "point " << q;
  }
  {
    ProbeTextures textures(device(), mixed);
    textures.upload(runner(), mixed);
    const auto results = Harness(device(), textures, brdf(), 2).run(runner(), queries);
    // The midpoint of cell (0,0,0): the mean of its 7 active corners, written out.
    glm::vec3 mean(0.0f);
    for (int k = 0; k < 8; ++k) {
      const std::uint32_t i = grid.index(glm::ivec3(k & 1, (k >> 1) & 1, k >> 2));
      if (i != centre) mean += sh::irradiance(mixed.sh(i), n) / 7.0f;
    }
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(results[3][c], mean[c], 1e-5f * mean[c]);
    for (std::size_t q = 0; q < points.size(); ++q) {
      bool valid = false;
      const glm::vec3 expected = sh::irradiance(cpu_interpolate(mixed, points[q], valid), n);
      EXPECT_TRUE(valid);
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(results[q][c], expected[c], 2e-3f * expected[c]) << "point " << q;
    }
  }
  {
    probes::ProbeVolume dead(probes::ProbeGrid(kBounds, {2, 2, 2}), 2);
    for (std::uint32_t i = 0; i < dead.probe_count(); ++i) dead.deactivate(i, true);
    ProbeTextures textures(device(), dead);
    textures.upload(runner(), dead);
    std::vector<Query> q = queries;
    q.push_back(l0_query(mid));
    q.push_back(specular_query(mid, n, 0.5f));
    const auto results = Harness(device(), textures, brdf(), 2).run(runner(), q);
    for (const glm::vec4& r : results) EXPECT_EQ(r, glm::vec4(0.0f));
  }
}

// A shader of a lower order reads a prefix of the slots of higher-order textures: L2 over L4
// textures gives the L2 truncation.
TEST_F(ProbeLightingTest, LowerShaderOrderReadsHigherOrderTextures) {
  std::mt19937 rng(23u);
  probes::ProbeVolume volume(probes::ProbeGrid(kBounds, {2, 2, 2}), 4);
  const sh::ShRgb s4 = random_sh(rng, 4, 1.0f, 0.2f, true);
  for (std::uint32_t i = 0; i < volume.probe_count(); ++i) volume.set_sh(i, s4);
  ProbeTextures textures(device(), volume);
  EXPECT_EQ(textures.texture_count(), 19u);
  textures.upload(runner(), volume);
  sh::ShRgb s2 = s4;
  s2.set_order(2);
  std::vector<Query> queries;
  std::vector<glm::vec3> expected;
  for (int q = 0; q < 16; ++q) {
    const glm::vec3 d = random_direction(rng);
    queries.push_back(irradiance_query(kBounds.center(), d));
    expected.push_back(glm::max(sh::irradiance(s2, d), glm::vec3(0.0f)));
  }
  const auto results = Harness(device(), textures, brdf(), 2).run(runner(), queries);
  for (std::size_t q = 0; q < queries.size(); ++q)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(results[q][c], expected[q][c], 1e-5f);
}

}  // namespace
}  // namespace ddish::raster::test
