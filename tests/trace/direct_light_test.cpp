// Direct lighting against closed forms: punctual lights (point, spot, directional), emitters
// seen directly, the environment. The BRDF value itself is Bsdf::eval (tested on its own in
// bsdf_test.cpp); these tests check everything around it: light units, distances, cosines,
// falloff, shadow rays and offsets. Paths here are deterministic (no area lights and nothing to
// bounce into), so they are asserted to float precision.
#include <cmath>

#include <gtest/gtest.h>

#include "trace/lights.h"
#include "trace/sampling.h"
#include "trace_test_scenes.h"

namespace ddish::trace {
namespace {

using testing::add_material;
using testing::add_quad;

constexpr float kRho = 0.6f;

scene::Scene plane_scene(const scene::Material& m) {
  scene::Scene s;
  // A 20 m × 20 m floor at y = 0 facing +y (a = z, b = x: cross(z, x) = +y).
  add_quad(s, {0, 0, 0}, {0, 0, 10}, {10, 0, 0}, add_material(s, m));
  return s;
}

// Radiance of the floor point at the origin seen from straight above.
glm::vec3 radiance_from_above(const scene::Scene& s, int bounces = 1) {
  PathOptions opt;
  opt.max_bounces = bounces;
  Tracer tracer(s, opt);
  Sampler sampler(1, 0);
  return tracer.trace_path(Ray{{0, 2, 0}, {0, -1, 0}}, sampler).radiance;
}

// The BRDF × cos(theta_i) for a viewer straight above and light arriving from wi_world.
glm::vec3 f_cos(const scene::Material& m, glm::vec3 wi_world) {
  const Bsdf bsdf({glm::vec3(m.base_color), m.metallic, m.roughness});
  // Floor frame: n = +y; local (x, y, z) = world (x, -z, y) keeps it right-handed.
  const glm::vec3 wi(wi_world.x, -wi_world.z, wi_world.y);
  return bsdf.eval({0, 0, 1}, wi) * wi.z;
}

TEST(DirectLight, PointLightAboveDiffusePlane) {
  const scene::Material m = testing::diffuse(glm::vec3(kRho), 1.0f);
  scene::Scene s = plane_scene(m);
  scene::Light light;
  light.type = scene::LightType::Point;
  light.intensity = 5.0f;  // W/sr
  light.position = {0, 3, 0};
  s.lights.push_back(light);
  const glm::vec3 l = radiance_from_above(s);
  // L = I / d² · f(n, n) · cos 0; with a pure Lambert BRDF this would be I ρ / (π d²).
  const glm::vec3 expected = 5.0f / 9.0f * f_cos(m, {0, 1, 0});
  EXPECT_NEAR(l.x, expected.x, 1e-5f * expected.x);
  // The dielectric layer changes the Lambert value by a few per cent, not more.
  EXPECT_NEAR(l.x, 5.0f * kRho / (kPi * 9.0f), 0.08f * l.x);
}

TEST(DirectLight, PointLightRangeWindow) {
  const scene::Material m = testing::diffuse(glm::vec3(kRho), 1.0f);
  scene::Scene s = plane_scene(m);
  scene::Light light;
  light.intensity = 5.0f;
  light.position = {0, 3, 0};
  light.range = 4.0f;  // glTF's window: clamp(1 - (d / range)^4, 0, 1)
  s.lights.push_back(light);
  const float window = 1.0f - std::pow(3.0f / 4.0f, 4.0f);
  const glm::vec3 expected = 5.0f * window / 9.0f * f_cos(m, {0, 1, 0});
  EXPECT_NEAR(radiance_from_above(s).x, expected.x, 1e-5f * expected.x);
  s.lights[0].range = 2.9f;
  EXPECT_EQ(radiance_from_above(s).x, 0.0f);
}

TEST(DirectLight, PointLightObliqueAndShadowed) {
  const scene::Material m = testing::diffuse(glm::vec3(kRho), 0.5f);
  scene::Scene s = plane_scene(m);
  scene::Light light;
  light.intensity = 4.0f;
  light.position = {3, 4, 0};  // d = 5, cos = 0.8
  s.lights.push_back(light);
  const glm::vec3 l = radiance_from_above(s);
  const glm::vec3 expected = 4.0f / 25.0f * f_cos(m, glm::vec3(3, 4, 0) / 5.0f);
  EXPECT_NEAR(l.y, expected.y, 1e-5f * expected.y);

  // A small occluder halfway along the light's path puts the point in shadow.
  add_quad(s, {1.5f, 2.0f, 0}, {0, 0, 0.2f}, {0.2f, 0, 0},
           add_material(s, testing::diffuse(glm::vec3(0.5f))));
  EXPECT_EQ(radiance_from_above(s).y, 0.0f);
}

TEST(DirectLight, SpotLightSmoothFalloff) {
  const scene::Material m = testing::diffuse(glm::vec3(kRho), 1.0f);
  scene::Scene s = plane_scene(m);
  scene::Light spot;
  spot.type = scene::LightType::Spot;
  spot.intensity = 10.0f;
  spot.inner_cone = 0.2f;
  spot.outer_cone = 0.4f;
  spot.direction = {0, -1, 0};
  s.lights.push_back(spot);
  const float h = 2.0f;
  for (float angle : {0.1f, 0.3f, 0.39f, 0.45f}) {
    // Move the light sideways so the floor point under the camera is `angle` off the spot axis.
    s.lights[0].position = {h * std::tan(angle), h, 0};
    const glm::vec3 to_light = glm::normalize(s.lights[0].position);
    const float d2 = glm::dot(s.lights[0].position, s.lights[0].position);
    float falloff = 1.0f;
    if (angle > 0.2f) {
      const float x = (std::cos(angle) - std::cos(0.4f)) / (std::cos(0.2f) - std::cos(0.4f));
      falloff = angle >= 0.4f ? 0.0f : x * x;
    }
    const glm::vec3 expected = 10.0f * falloff / d2 * f_cos(m, to_light);
    const glm::vec3 l = radiance_from_above(s);
    EXPECT_NEAR(l.x, expected.x, 1e-5f * std::max(expected.x, 1e-3f)) << "angle " << angle;
  }
}

TEST(DirectLight, DirectionalLightIrradiance) {
  const scene::Material m = testing::diffuse(glm::vec3(kRho), 0.8f, 0.2f);
  scene::Scene s = plane_scene(m);
  scene::Light sun;
  sun.type = scene::LightType::Directional;
  sun.intensity = 3.0f;  // irradiance on a surface facing it
  sun.color = {1.0f, 0.5f, 0.25f};
  const glm::vec3 to_sun = glm::normalize(glm::vec3(0.5f, 1.0f, 0.3f));
  sun.direction = -to_sun;
  s.lights.push_back(sun);
  const glm::vec3 l = radiance_from_above(s);
  // L = E · f · cos(theta_sun): E arrives on the tilted floor as E cos.
  const glm::vec3 expected = 3.0f * sun.color * f_cos(m, to_sun);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(l[c], expected[c], 1e-5f * expected[c]);
}

TEST(DirectLight, EmitterSeenDirectlyIsExact) {
  scene::Scene s;
  const glm::vec3 le(2.0f, 4.0f, 8.0f);
  add_quad(s, {0, 0, -5}, {1, 0, 0}, {0, 1, 0}, add_material(s, testing::emitter(le)));  // faces +z
  for (int bounces : {0, 1, 6}) {
    PathOptions opt;
    opt.max_bounces = bounces;
    Tracer tracer(s, opt);
    Sampler sampler(3, 1);
    const PathSample p = tracer.trace_path(Ray{{0.2f, 0.1f, 0}, {0, 0, -1}}, sampler);
    EXPECT_TRUE(p.hit);
    EXPECT_FALSE(p.backface);
    EXPECT_NEAR(p.hit_distance, 5.0f, 1e-5f);
    EXPECT_EQ(p.radiance, le) << bounces;
  }
  // From behind, the single-sided emitter is a back face: no light, and it is reported.
  Tracer tracer(s);
  Sampler sampler(3, 1);
  const PathSample back = tracer.trace_path(Ray{{0, 0, -9}, {0, 0, 1}}, sampler);
  EXPECT_TRUE(back.backface);
  EXPECT_EQ(back.radiance, glm::vec3(0.0f));
}

TEST(DirectLight, EscapingRayReturnsEnvironment) {
  scene::Scene s = plane_scene(testing::diffuse(glm::vec3(kRho)));
  s.sidecar.environment = {0.5f, 1.0f, 2.0f};
  Tracer tracer(s);
  Sampler sampler(1, 2);
  const PathSample p = tracer.trace_path(Ray{{0, 1, 0}, glm::normalize(glm::vec3(1, 2, 3))}, sampler);
  EXPECT_FALSE(p.hit);
  EXPECT_EQ(p.radiance, s.sidecar.environment);
}

TEST(DirectLight, DiffusePlaneUnderUniformSky) {
  // One bounce under a sky of radiance L: the floor reflects L × its directional albedo, which
  // for a Lambert BRDF is ρ; the glTF BRDF's albedo comes from quadrature of Bsdf::eval.
  const scene::Material m = testing::diffuse(glm::vec3(kRho), 0.7f);
  scene::Scene s = plane_scene(m);
  const float sky = 1.5f;
  s.sidecar.environment = glm::vec3(sky);
  PathOptions opt;
  opt.max_bounces = 1;
  Tracer tracer(s, opt);
  const testing::Estimate e = testing::estimate(tracer, Ray{{0, 2, 0}, {0, -1, 0}}, 20000);
  const glm::dvec3 albedo = testing::directional_albedo(Bsdf({glm::vec3(kRho), 0.0f, 0.7f}), {0, 0, 1});
  const double expected = sky * albedo.x;
  testing::report("floor under uniform sky", e.mean.x, e.stderr_.x, expected);
  EXPECT_NEAR(e.mean.x, expected, 4.0 * e.stderr_.x + 1e-4 * expected);
  EXPECT_NEAR(albedo.x, kRho, 0.05);  // close to the Lambert value ρ
  EXPECT_EQ(tracer.invalid_paths(), 0u);
}

TEST(Lights, SpotAttenuationMatchesGltfFormula) {
  scene::Light spot;
  spot.type = scene::LightType::Spot;
  spot.inner_cone = 0.3f;
  spot.outer_cone = 0.6f;
  spot.direction = {0, 0, -1};
  EXPECT_FLOAT_EQ(spot_attenuation(spot, {0, 0, -1}), 1.0f);
  EXPECT_FLOAT_EQ(spot_attenuation(spot, {std::sin(0.7f), 0, -std::cos(0.7f)}), 0.0f);
  const float x = (std::cos(0.45f) - std::cos(0.6f)) / (std::cos(0.3f) - std::cos(0.6f));
  EXPECT_NEAR(spot_attenuation(spot, {std::sin(0.45f), 0, -std::cos(0.45f)}), x * x, 1e-5f);
}

}  // namespace
}  // namespace ddish::trace
