// Visibility-aware probe interpolation (shaders/include/probe_lighting.glsl with a volume that
// has distance moments): for known moments, the GPU's result against the formula written out
// here (per probe trilinear x backface x Chebyshev, crushed; folded per axis into the trilinear
// fractions; inactive probes weighted out by the validity renormalisation), and moments that see
// nothing in the way giving the backface-weighted mean exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "probe_lighting_harness.h"
#include "probe_test_util.h"
#include "sh/packing.h"

namespace ddish::raster::test {
namespace {

class ProbeVisibilityTest : public ProbeGpuTest {};

float as_half(float v) { return sh::half_to_float(sh::float_to_half(v)); }

// The weight of one probe as probe_lighting.glsl defines it, from the moments as the GPU sees
// them (fp16).
double visibility_weight(const probes::ProbeVolume& v, std::uint32_t i, const glm::vec3& p,
                         const glm::vec3& n, double trilinear) {
  const glm::vec3 probe = v.position(i);  // relocated
  const glm::vec3 to_probe = glm::normalize(probe - p);
  double w = (double(glm::dot(to_probe, n)) + 1.0) * 0.5;
  w = w * w + 0.2;
  const float bias = kVisibilityBiasCells * 1.0f;  // cells of 1 m
  const glm::vec3 biased = p + bias * n;            // 0.2 n + 0.8 v with v = n
  const glm::vec3 from = biased - probe;
  const double r = double(glm::length(from)) / v.moment_range();
  const glm::vec2 m = v.moments(i)[probes::moment_texel(glm::normalize(from), v.moment_resolution())];
  const double mean = as_half(m.x), mean2 = as_half(m.y);
  if (r > mean) {
    const double var = std::max(mean2 - mean * mean, 1e-4);
    const double c = var / (var + (r - mean) * (r - mean));
    w *= c * c * c;
  }
  w = std::max(w, 1e-6);
  if (w < 0.2) w = w * w * w / 0.04;
  return trilinear * w;
}

}  // namespace

TEST_F(ProbeVisibilityTest, ChebyshevWeightsOfKnownMomentsMatchTheFormula) {
  // 2 x 2 x 2 probes, 1 m apart at 0.5 and 1.5 on each axis; probe i holds L0 = 2^i (exact in
  // fp16), so the result identifies the weights.
  probes::ProbeVolume v(probes::ProbeGrid(scene::Aabb{glm::vec3(0.0f), glm::vec3(2.0f)}, {2, 2, 2}),
                        2, 4);
  ASSERT_NEAR(v.moment_range(), 1.5f * std::sqrt(3.0f), 1e-5f);
  for (std::uint32_t i = 0; i < 8; ++i) {
    sh::ShRgb s(2);
    s[0] = glm::vec3(float(1u << i));
    v.set_sh(i, s);
  }
  // Probe 0 sees a wall at a tenth of the range in every direction (spread 0.05), probe 3 at
  // 0.3 (spread 0.1), probe 5 one texel of geometry (the direction to the query point only);
  // the others see nothing in the range.
  for (glm::vec2& t : v.moments(0)) t = {0.1f, 0.1f * 0.1f + 0.05f * 0.05f};
  for (glm::vec2& t : v.moments(3)) t = {0.3f, 0.3f * 0.3f + 0.1f * 0.1f};
  v.deactivate(6, false);  // inactive: weighted out whatever its moments
  v.set_offset(3, {0.1f, -0.2f, 0.05f});  // relocated: its distances are measured from there

  const std::vector<glm::vec3> points = {{0.9f, 1.1f, 0.7f}, {0.6f, 0.6f, 0.6f}, {1.4f, 0.55f, 1.2f}};
  const std::vector<glm::vec3> normals = {glm::normalize(glm::vec3(0.3f, 0.8f, -0.5f)),
                                          glm::vec3(-1.0f, 0.0f, 0.0f),
                                          glm::normalize(glm::vec3(0.0f, -1.0f, 1.0f))};
  {
    const glm::vec3 p = points[2];
    const glm::vec3 from = p + kVisibilityBiasCells * normals[2] - v.position(5u);
    v.moments(5)[probes::moment_texel(glm::normalize(from), 4)] = {0.05f, 0.05f * 0.05f + 1e-4f};
  }
  std::vector<Query> queries;
  for (std::size_t q = 0; q < points.size(); ++q) queries.push_back(visible_l0_query(points[q], normals[q]));
  ProbeTextures textures(device(), v);
  textures.upload(runner(), v);
  const auto results = Harness(device(), textures, brdf(), 2).run(runner(), queries);
  auto trilinear = [](const glm::dvec3& t, glm::ivec3 o) {
    return (o.x ? t.x : 1.0 - t.x) * (o.y ? t.y : 1.0 - t.y) * (o.z ? t.z : 1.0 - t.z);
  };
  for (std::size_t q = 0; q < points.size(); ++q) {
    const glm::dvec3 t = glm::dvec3(points[q]) - 0.5;  // trilinear fractions in the one cell
    double sum_w = 0.0, w0 = 0.0;
    glm::dvec3 upper(0.0);
    for (std::uint32_t i = 0; i < 8; ++i) {
      const glm::ivec3 o(int(i & 1u), int((i >> 1) & 1u), int(i >> 2));
      const double w = visibility_weight(v, i, points[q], normals[q], trilinear(t, o));
      if (i == 0) w0 = w;
      sum_w += w;
      upper += w * glm::dvec3(o);
    }
    // The weights folded per axis, then trilinear at the moved fractions over the active probes.
    const glm::dvec3 moved = upper / sum_w;
    double sum = 0.0, valid = 0.0;
    for (std::uint32_t i = 0; i < 8; ++i) {
      if (!v.state(i).active()) continue;
      const double w = trilinear(moved, glm::ivec3(int(i & 1u), int((i >> 1) & 1u), int(i >> 2)));
      sum += w * double(1u << i);
      valid += w;
    }
    const double expected = sum / valid;
    EXPECT_EQ(results[q].w, 1.0f);
    EXPECT_NEAR(results[q].x, expected, 1e-3 * expected) << "point " << q;
    if (q == 0) {
      EXPECT_LT(w0, 1e-3 * sum_w) << "probe 0's wall hides it from the point";
    }
  }
}

TEST_F(ProbeVisibilityTest, ClearMomentsGiveTheBackfaceWeightedMeanAndDeadCellsGiveNothing) {
  // Moments that see nothing within the range: Chebyshev is 1, only trilinear x backface stays.
  // A point at the cell's centre with normal +x: probes at x = 1.5 face it (cos = 1/sqrt(3)),
  // those at 0.5 do not (cos = -1/sqrt(3)).
  probes::ProbeVolume v(probes::ProbeGrid(scene::Aabb{glm::vec3(0.0f), glm::vec3(2.0f)}, {2, 2, 2}),
                        2, 8);
  for (std::uint32_t i = 0; i < 8; ++i) {
    sh::ShRgb s(2);
    s[0] = glm::vec3((i & 1u) ? 4.0f : 1.0f);
    v.set_sh(i, s);
  }
  ProbeTextures textures(device(), v);
  textures.upload(runner(), v);
  std::vector<Query> q = {visible_l0_query(glm::vec3(1.0f), glm::vec3(1.0f, 0.0f, 0.0f))};
  auto results = Harness(device(), textures, brdf(), 2).run(runner(), q);
  const double c = 1.0 / std::sqrt(3.0);
  const double front = std::pow((1.0 + c) / 2.0, 2.0) + 0.2;
  const double back = std::pow((1.0 - c) / 2.0, 2.0) + 0.2;
  EXPECT_NEAR(results[0].x, (4.0 * front + 1.0 * back) / (front + back), 1e-4);

  for (std::uint32_t i = 0; i < 8; ++i) v.deactivate(i, true);
  textures.upload(runner(), v);
  results = Harness(device(), textures, brdf(), 2).run(runner(), q);
  EXPECT_EQ(results[0], glm::vec4(0.0f));
}

// The weights depend on ratios only (distances over the moment range, the bias in cells), so a
// scene scaled from a millimetre to ten kilometres gives the same result, and a finite one.
TEST_F(ProbeVisibilityTest, TheSameWeightsFromAMillimetreToTenKilometres) {
  std::vector<float> results;
  for (float k : {1e-3f, 1.0f, 1e4f}) {
    probes::ProbeVolume v(
        probes::ProbeGrid(scene::Aabb{glm::vec3(0.0f), glm::vec3(2.0f * k)}, {2, 2, 2}), 2, 8);
    for (std::uint32_t i = 0; i < 8; ++i) {
      sh::ShRgb s(2);
      s[0] = glm::vec3(float(1u << i));
      v.set_sh(i, s);
      // A wall a tenth of the range from every probe on the x = 0.5 side.
      if ((i & 1u) == 0)
        for (glm::vec2& t : v.moments(i)) t = {0.1f, 0.1f * 0.1f + 0.02f * 0.02f};
    }
    ProbeTextures textures(device(), v);
    textures.upload(runner(), v);
    const std::vector<Query> q = {visible_l0_query(glm::vec3(1.3f, 0.8f, 1.1f) * k,
                                                   glm::normalize(glm::vec3(1.0f, 0.2f, -0.1f)))};
    const auto r = Harness(device(), textures, brdf(), 2).run(runner(), q);
    ASSERT_TRUE(std::isfinite(r[0].x)) << "scale " << k;
    results.push_back(r[0].x);
  }
  EXPECT_NEAR(results[0], results[1], 1e-3f * results[1]);
  EXPECT_NEAR(results[2], results[1], 1e-3f * results[1]);
  // The wall hides the x = 0.5 probes (even L0 values): the result lies near the odd ones' mean.
  EXPECT_GT(results[1], 2.0f * 1.0f);
}

}  // namespace ddish::raster::test
