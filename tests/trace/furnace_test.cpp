// Furnaces and area lights: setups whose answer is derived, not measured.
//
// 1. Emissive enclosure, one scattering. Inside a closed box whose walls all emit Le and reflect
//    with some BSDF f, every direction leaving a wall point sees another wall, i.e. exactly Le.
//    So the one-bounce radiance seen from the centre is Le + Le·A(wo), A = ∫ f cos dwi (the
//    wall's directional albedo, by quadrature of Bsdf::eval), whatever the wall's shape or
//    BSDF. The integrator gets there by NEE on the emissive triangles plus BSDF-sampled hits of
//    the same triangles, MIS-weighted: a wrong weight or pdf breaks the sum. Run at 1e-3, 1 and
//    1e4 metre scales (ray offsets) and off the origin.
// 2. White furnace: a white dielectric (albedo 1 at every angle, by the BSDF's design) inside a
//    uniform environment L, in a concave shape (an open box) where paths bounce many times with
//    Russian roulette: every path's expectation is L.
// 3. A diffuse floor under an emissive square: the MIS estimate converges to the quadrature of
//    Le f cos cos / r² over the square, itself checked against the closed-form point-to-parallel-
//    rectangle form factor.
#include <cmath>

#include <gtest/gtest.h>

#include "trace/sampling.h"
#include "trace_test_scenes.h"

namespace ddish::trace {
namespace {

using testing::add_material;
using testing::add_quad;

struct FurnaceCase {
  float scale;
  float roughness;
  float metallic;
};

class EmissiveEnclosure : public ::testing::TestWithParam<FurnaceCase> {};

TEST_P(EmissiveEnclosure, OneBounceIsLeTimesOnePlusAlbedo) {
  const FurnaceCase fc = GetParam();
  const glm::vec3 base(0.7f, 0.5f, 0.3f);
  scene::Material wall = testing::diffuse(base, fc.roughness, fc.metallic);
  const float le = 2.0f;
  wall.emissive = glm::vec3(le);
  scene::Scene s;
  const glm::vec3 centre = fc.scale * glm::vec3(10.0f, -7.0f, 3.0f);
  const glm::vec3 half(fc.scale);
  testing::add_box_inward(s, centre - half, centre + half, add_material(s, wall));

  PathOptions opt;
  opt.max_bounces = 0;
  {
    Tracer tracer(s, opt);
    Sampler sampler(1, 0);
    EXPECT_EQ(tracer.trace_path(Ray{centre, {1, 0, 0}}, sampler).radiance, glm::vec3(le));
  }
  opt.max_bounces = 1;
  Tracer tracer(s, opt);
  // Looking at a wall centre at normal incidence: wo = n.
  const int n = 40000;
  const testing::Estimate e = testing::estimate(tracer, Ray{centre, {1, 0, 0}}, n);
  const glm::dvec3 albedo = testing::directional_albedo(Bsdf({base, fc.metallic, fc.roughness}), {0, 0, 1});
  for (int c = 0; c < 3; ++c) {
    const double expected = le * (1.0 + albedo[c]);
    testing::report("emissive enclosure, one bounce", e.mean[c], e.stderr_[c], expected);
    EXPECT_NEAR(e.mean[c], expected, 4.0 * e.stderr_[c] + 2e-4 * expected) << "channel " << c;
  }
  EXPECT_EQ(tracer.invalid_paths(), 0u);
  // A primary and a BSDF ray per path, plus a shadow ray unless NEE picked the hit's own face.
  EXPECT_GT(tracer.rays_traced(), 2u * n);
  EXPECT_LE(tracer.rays_traced(), 3u * n);
}

TEST(EmissiveEnclosureOptions, IndirectClampAndRussianRoulette) {
  const glm::vec3 base(0.6f);
  scene::Material wall = testing::diffuse(base, 0.7f);
  const float le = 1.0f;
  wall.emissive = glm::vec3(le);
  scene::Scene s;
  testing::add_box_inward(s, {-1, -1, -1}, {1, 1, 1}, add_material(s, wall));
  const Ray ray{{0, 0, 0}, {1, 0, 0}};
  const double one_bounce = le * (1.0 + testing::directional_albedo(Bsdf({base, 0.0f, 0.7f}), {0, 0, 1}).x);

  // Clamping every contribution that scattered twice or more to (almost) nothing leaves exactly
  // the emission and the first scattering.
  PathOptions opt;
  opt.max_bounces = 4;
  opt.rr_min_bounces = 100;
  opt.indirect_clamp = 1e-9f;
  Tracer clamped(s, opt);
  const testing::Estimate c = testing::estimate(clamped, ray, 20000);
  testing::report("indirect clamp leaves one bounce", c.mean.x, c.stderr_.x, one_bounce);
  EXPECT_NEAR(c.mean.x, one_bounce, 4.0 * c.stderr_.x + 1e-4);

  // Russian roulette changes the variance, not the expectation.
  opt.indirect_clamp = 0.0f;
  Tracer no_rr(s, opt);
  opt.rr_min_bounces = 1;
  Tracer rr(s, opt);
  const testing::Estimate a = testing::estimate(no_rr, ray, 20000, 11);
  const testing::Estimate b = testing::estimate(rr, ray, 20000, 12);
  EXPECT_GT(a.mean.x, one_bounce + 0.1);  // more bounces, more light
  testing::report("Russian roulette vs none", b.mean.x, std::hypot(a.stderr_.x, b.stderr_.x), a.mean.x);
  EXPECT_NEAR(a.mean.x, b.mean.x, 4.0 * std::hypot(a.stderr_.x, b.stderr_.x));
  EXPECT_LT(rr.rays_traced(), no_rr.rays_traced());
}

INSTANTIATE_TEST_SUITE_P(Scales, EmissiveEnclosure,
                         ::testing::Values(FurnaceCase{1.0f, 0.6f, 0.0f}, FurnaceCase{1.0f, 0.3f, 1.0f},
                                           FurnaceCase{1e-3f, 0.6f, 0.3f}, FurnaceCase{1e4f, 0.6f, 0.3f}));

TEST(WhiteFurnace, OpenBoxInUniformEnvironmentSeesEnvironment) {
  scene::Scene s;
  scene::Material white = testing::diffuse(glm::vec3(1.0f), 0.5f, 0.0f);
  white.double_sided = true;
  testing::add_box_inward(s, {-1, -1, -1}, {1, 1, 1}, add_material(s, white), /*open_top=*/true);
  s.sidecar.environment = glm::vec3(1.0f);
  PathOptions opt;
  opt.max_bounces = 200;
  opt.rr_min_bounces = 3;
  Tracer tracer(s, opt);
  // Looking down into the box: paths bounce between the walls until they leave by the top.
  const testing::Estimate e = testing::estimate(
      tracer, Ray{{0.3f, 3.0f, 0.2f}, glm::normalize(glm::vec3(-0.1f, -1.0f, 0.05f))}, 40000);
  // The BSDF's albedo of 1 comes from a tabulated layer albedo; 0.5 % covers its table error.
  testing::report("white furnace, open box", e.mean.x, e.stderr_.x, 1.0);
  EXPECT_NEAR(e.mean.x, 1.0, 4.0 * e.stderr_.x + 5e-3);
  EXPECT_EQ(tracer.invalid_paths(), 0u);
}

// Closed form: form factor from a point to a parallel w × l rectangle at height h with a corner
// straight above the point.
double corner_form_factor(double w, double l, double h) {
  const double a = w / h;
  const double b = l / h;
  const double sa = std::sqrt(1.0 + a * a);
  const double sb = std::sqrt(1.0 + b * b);
  return (a / sa * std::atan(b / sa) + b / sb * std::atan(a / sb)) / (2.0 * M_PI);
}

struct AreaCase {
  float half_size;
  float height;
  float roughness;
};

class AreaLight : public ::testing::TestWithParam<AreaCase> {};

TEST_P(AreaLight, MisConvergesToQuadrature) {
  const AreaCase ac = GetParam();
  const glm::vec3 base(0.6f);
  const float le = 3.0f;
  scene::Scene s;
  add_quad(s, {0, 0, 0}, {0, 0, 10}, {10, 0, 0}, add_material(s, testing::diffuse(base, ac.roughness)));
  // The square emitter faces down (-y): a = x, b = z, cross(x, z) = -y.
  add_quad(s, {0, ac.height, 0}, {ac.half_size, 0, 0}, {0, 0, ac.half_size},
           add_material(s, testing::emitter(glm::vec3(le))));
  PathOptions opt;
  opt.max_bounces = 1;
  Tracer tracer(s, opt);
  const testing::Estimate e = testing::estimate(tracer, Ray{{0, 0.5f * ac.height, 0}, {0, -1, 0}}, 30000);

  // Quadrature over the square of Le f(wo, wi) cos_i cos_l / r² (floor frame: local = (x, -z, y)).
  const Bsdf bsdf({base, 0.0f, ac.roughness});
  const int n = 400;
  const double da = (2.0 * ac.half_size / n) * (2.0 * ac.half_size / n);
  double radiance = 0.0;
  double form_factor = 0.0;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double x = -ac.half_size + (i + 0.5) * 2.0 * ac.half_size / n;
      const double z = -ac.half_size + (j + 0.5) * 2.0 * ac.half_size / n;
      const double r2 = x * x + z * z + double(ac.height) * ac.height;
      const double cos_i = ac.height / std::sqrt(r2);  // = cos at the light (parallel planes)
      const glm::vec3 wi = glm::normalize(glm::vec3(float(x), float(-z), ac.height));
      const double g = cos_i * cos_i / r2 * da;
      radiance += le * double(bsdf.eval({0, 0, 1}, wi).x) * g;
      form_factor += g / M_PI;
    }
  }
  const double hs = ac.half_size;
  EXPECT_NEAR(form_factor, 4.0 * corner_form_factor(hs, hs, ac.height), 1e-4 * form_factor);
  testing::report("floor under an emissive square (MIS)", e.mean.x, e.stderr_.x, radiance);
  EXPECT_NEAR(e.mean.x, radiance, 4.0 * e.stderr_.x + 1e-3 * radiance);
  EXPECT_EQ(tracer.invalid_paths(), 0u);
}

// A large close emitter (BSDF sampling carries much of the weight) and a small distant one
// (almost a point: NEE carries it), rough and fairly glossy floors.
INSTANTIATE_TEST_SUITE_P(Configurations, AreaLight,
                         ::testing::Values(AreaCase{2.0f, 0.5f, 1.0f}, AreaCase{0.05f, 3.0f, 1.0f},
                                           AreaCase{1.0f, 1.0f, 0.25f}));

}  // namespace
}  // namespace ddish::trace
