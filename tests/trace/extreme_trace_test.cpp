// Stiff and extreme cases of the path tracer (docs/extreme-cases.md), end to end through
// Tracer::trace_path: a sunlit floor with an occluder at 1e-3, 1 and 1e4 metre scale (the
// shadow is where geometry puts it, no acne, no leaks), and a 1e6 emitter beside dim surfaces.
// Already covered elsewhere: ray offsets at these scales at the Embree level
// (robustness_test.cpp, Scales/RayOffset.NoSelfIntersection), degenerate triangles
// (Tracer.DegenerateTrianglesGiveFiniteRadiance), roughness 0 and 1 and grazing angles in the
// BSDF (bsdf_test.cpp, Bsdf.FiniteAtTheExtremes), non-finite radiance caught and counted
// (Tracer.NonFiniteRadianceIsCaughtAndCounted).
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "trace/bsdf.h"
#include "trace/tracer.h"
#include "trace_test_scenes.h"

namespace ddish::trace {
namespace {

using testing::add_material;
using testing::add_quad;

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

class SceneScale : public ::testing::TestWithParam<float> {};

// A 20 x 20 floor (y = 0, facing +y) and a 2 x 2 occluder 1 above it, all times `scale`, under
// a directional light (irradiance 3) from to_sun. Seen straight from above (from half-way up,
// under the occluder) on a 48 x 48 grid of floor points, with direct light only (max_bounces 1): a point is in shadow exactly when the
// ray towards the sun crosses the occluder. Points within 1 % of the scale of the shadow's
// edge are left out (the edge itself is a measure-zero set). Every lit point must have the
// closed-form radiance E f cos to 1e-4 (acne would darken some) and every shadowed one
// exactly 0 (a leak would light it): the bound is zero wrong points of about 2000 (a single
// self-shadowed point would show), at every scale.
TEST_P(SceneScale, SunShadowOfAnOccluderIsExactWithoutAcne) {
  const float scale = GetParam();
  scene::Scene s;
  const scene::Material floor_material = testing::diffuse(glm::vec3(0.6f), 0.8f, 0.0f);
  add_quad(s, {0, 0, 0}, {0, 0, 10 * scale}, {10 * scale, 0, 0}, add_material(s, floor_material));
  add_quad(s, {0, scale, 0}, {0, 0, scale}, {scale, 0, 0},
           add_material(s, testing::diffuse(glm::vec3(0.5f))));  // faces +y, lit on top
  scene::Light sun;
  sun.type = scene::LightType::Directional;
  sun.intensity = 3.0f;
  const glm::vec3 to_sun = glm::normalize(glm::vec3(0.5f, 1.0f, 0.3f));
  sun.direction = -to_sun;
  s.lights.push_back(sun);
  PathOptions opt;
  opt.max_bounces = 1;
  Tracer tracer(s, opt);
  const Bsdf bsdf({glm::vec3(0.6f), 0.0f, 0.8f});
  // Floor frame: n = +y; local (x, y, z) = world (x, -z, y).
  const float expected = 3.0f * bsdf.eval({0, 0, 1}, {to_sun.x, -to_sun.z, to_sun.y}).x * to_sun.y;
  int lit = 0, shadowed = 0, acne = 0, leaks = 0;
  float worst = 0.0f;
  for (int i = 0; i < 48; ++i)
    for (int j = 0; j < 48; ++j) {
      // Points over [-4, 4]^2 (times scale) around the shadow.
      const glm::vec3 p = scale * glm::vec3(-4.0f + 8.0f * (float(i) + 0.5f) / 48.0f, 0.0f,
                                            -4.0f + 8.0f * (float(j) + 0.5f) / 48.0f);
      // Where the ray to the sun crosses the occluder's plane y = scale, in occluder units.
      const glm::vec3 q = (p + to_sun * (scale / to_sun.y)) / scale;
      const float edge = std::max(std::abs(q.x), std::abs(q.z));
      if (std::abs(edge - 1.0f) < 0.01f) continue;
      const bool in_shadow = edge < 1.0f;
      Sampler sampler(1, std::uint64_t(i * 48 + j));
      const glm::vec3 l = tracer.trace_path(Ray{p + glm::vec3(0.0f, 0.5f * scale, 0.0f), {0, -1, 0}}, sampler).radiance;
      ASSERT_TRUE(finite(l)) << i << "," << j;
      if (in_shadow) {
        ++shadowed;
        if (l.x != 0.0f) ++leaks;
      } else {
        ++lit;
        const float err = std::abs(l.x - expected) / expected;
        worst = std::max(worst, err);
        if (err > 1e-4f) ++acne;
      }
    }
  std::printf("[extreme] scale %g: %d lit (%d darkened, worst %.2e), %d shadowed (%d lit)\n",
              double(scale), lit, acne, double(worst), shadowed, leaks);
  EXPECT_GT(lit, 1500);
  EXPECT_GT(shadowed, 100);
  EXPECT_EQ(acne, 0);
  EXPECT_EQ(leaks, 0);
  EXPECT_EQ(tracer.invalid_paths(), 0u);
}

INSTANTIATE_TEST_SUITE_P(Scales, SceneScale, ::testing::Values(1e-3f, 1.0f, 1e4f));

// A 0.1 x 0.1 m emitter of radiance 1e6 facing down 1 m above a dim grey floor (albedo 0.5,
// sky 1e-3). Rays straight down at floor points: every path is finite and non-negative, and
// bounded: the floor is the only surface that scatters (the emitter is black), so a path is its
// next-event estimate, at most f Le A / d^2 <= (1.1 x 0.5 / pi) 1e6 x 0.01 / 1 = 1751 (the
// albedo-scaled diffuse lobe is at most 1 / (1 - E_avg) < 1.1 times Lambert), plus one
// BSDF-sampled hit of the emitter, weighted at most 1.1 x 0.5, so below 5.6e5 in all. Under the
// emitter's centre the mean is f(n, n) Le A (the emitter is small: cos^4 falloff over it < 1 %).
TEST(ExtremeTrace, BrightEmitterBesideDimSurfacesIsFiniteAndBounded) {
  scene::Scene s;
  s.sidecar.environment = glm::vec3(1e-3f);
  const scene::Material grey = testing::diffuse(glm::vec3(0.5f));
  add_quad(s, {0, 0, 0}, {0, 0, 5}, {5, 0, 0}, add_material(s, grey));
  add_quad(s, {0, 1, 0}, {0.05f, 0, 0}, {0, 0, 0.05f},
           add_material(s, testing::emitter(glm::vec3(1e6f))));  // cross(x, z) = -y: faces down
  PathOptions opt;
  opt.max_bounces = 4;
  Tracer tracer(s, opt);
  double max_l = 0.0;
  for (int i = 0; i < 400; ++i) {
    Sampler sampler(5, std::uint64_t(i));
    const glm::vec3 p(-1.0f + 0.1f * float(i % 20) + 0.05f, 0.5f, -1.0f + 0.1f * float(i / 20) + 0.05f);
    const glm::vec3 l = tracer.trace_path(Ray{p, {0, -1, 0}}, sampler).radiance;
    ASSERT_TRUE(finite(l)) << i;
    EXPECT_GE(std::min({l.x, l.y, l.z}), 0.0f) << i;
    max_l = std::max(max_l, double(l.x));
  }
  const Bsdf bsdf({glm::vec3(0.5f), 0.0f, 1.0f});
  const double expected = double(bsdf.eval({0, 0, 1}, {0, 0, 1}).x) * 1e6 * 0.01;
  double sum = 0.0;
  const int n = 2000;
  for (int i = 0; i < n; ++i) {
    Sampler sampler(6, std::uint64_t(i));
    sum += tracer.trace_path(Ray{{0.0f, 0.5f, 0.0f}, {0, -1, 0}}, sampler).radiance.x;
  }
  std::printf("[extreme] 1e6 emitter over a dim floor: max path radiance %.4g (bound 5.6e5), "
              "mean under it %.5g (expected %.5g)\n",
              max_l, sum / n, expected);
  EXPECT_LE(max_l, 5.6e5);
  EXPECT_NEAR(sum / n, expected, 0.03 * expected);
  EXPECT_EQ(tracer.invalid_paths(), 0u);
}

}  // namespace
}  // namespace ddish::trace
