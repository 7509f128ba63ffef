// Direct light in the rasterizer against the path tracer's own light and BSDF code: a glossy
// ground lit by one punctual light (spot, point, directional) with a sphere casting a shadow,
// probes switched off, so every pixel is exactly f(wo, wi) cos(theta) * the light's arriving
// radiance (trace::sample_punctual, trace::Bsdf) where the sphere does not block the light, and
// dark where it does. Checks the BSDF and the light falloffs match, that the shadow maps of all
// three kinds (perspective, cube, cascades) neither leak nor self-shadow, and how many shadow
// passes each light costs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "../gpu/gpu_test.h"
#include "probes/probe_grid.h"
#include "probes/probe_volume.h"
#include "raster/renderer.h"
#include "raster_scenes.h"
#include "scene/view.h"
#include "trace/bsdf.h"
#include "trace/lights.h"

namespace ddish::raster::test {
namespace {

using gpu::test::GpuTest;

constexpr float kHalf = 2.0f;
const glm::vec3 kSphereCenter(0.0f, 0.8f, 0.0f);
constexpr float kSphereRadius = 0.3f;

// Distance from the sphere's centre to the segment p -> p + wi * dist (the shadow ray).
float ray_clearance(const glm::vec3& p, const glm::vec3& wi, float dist) {
  const float t = std::clamp(glm::dot(kSphereCenter - p, wi), 0.0f, dist);
  return glm::length(p + wi * t - kSphereCenter);
}

struct Case {
  std::string name;
  scene::Light light;
  glm::vec3 position;
  glm::vec3 direction;
  std::uint32_t shadow_passes;
};

class DirectLightTest : public GpuTest, public ::testing::WithParamInterface<int> {};

Case make_case(int i) {
  scene::Light l;
  l.color = {1.0f, 0.9f, 0.8f};
  if (i == 0) {
    l.name = "spot";
    l.type = scene::LightType::Spot;
    l.intensity = 20.0f;
    l.inner_cone = 0.4f;
    l.outer_cone = 0.7f;
    return {"spot", l, {0.3f, 2.5f, 0.4f}, {-0.1f, -1.0f, -0.15f}, 1};
  }
  if (i == 1) {
    l.name = "point";
    l.type = scene::LightType::Point;
    l.intensity = 10.0f;
    l.range = 6.0f;
    return {"point", l, {0.4f, 2.0f, 0.3f}, {0.0f, -1.0f, 0.0f}, 6};
  }
  l.name = "sun";
  l.type = scene::LightType::Directional;
  l.intensity = 3.0f;
  return {"directional", l, {0.0f, 5.0f, 0.0f}, {-0.3f, -1.0f, -0.2f}, 3};
}

TEST_P(DirectLightTest, MatchesTracerBsdfAndShadows) {
  const Case c = make_case(GetParam());
  const scene::Material ground_material = make_material({0.7f, 0.6f, 0.5f}, 0.3f, 0.45f);
  scene::Scene s = one_mesh_scene(ground_quad(kHalf), ground_material);
  add_instance(s, uv_sphere(kSphereRadius, 48, 24), make_material({0.8f, 0.8f, 0.8f}, 0.0f, 0.8f),
               kSphereCenter);
  add_light(s, c.light, c.position, c.direction);
  const scene::Light& light = s.lights.front();

  const probes::ProbeVolume volume(probes::ProbeGrid(s.bounds(), {2, 2, 2}));
  RendererOptions options;
  options.msaa = 1;  // pixel centres are exactly where the expected values are computed
  options.probes = false;
  Renderer renderer(device(), s, volume, options);
  const int size = 96;
  const scene::View view = scene::look_at_view({0.0f, 3.5f, 3.5f}, {0.0f, 0.0f, 0.0f},
                                               {0.0f, 1.0f, 0.0f}, glm::radians(50.0f), size, size);
  const FrameOutput out = renderer.render(s, std::span(&view, 1));
  EXPECT_EQ(out.stats.shadow_passes, c.shadow_passes) << c.name;
  EXPECT_EQ(out.stats.forward_passes, 1u);

  const trace::Bsdf bsdf({glm::vec3(ground_material.base_color), ground_material.metallic,
                          ground_material.roughness});
  ShadowTally tally;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const scene::Ray ray = scene::view_ray(view, float(x) + 0.5f, float(y) + 0.5f);
      if (ray.direction.y >= 0.0f) continue;
      const glm::vec3 p = ray.origin + ray.direction * (-ray.origin.y / ray.direction.y);
      if (std::abs(p.x) > kHalf - 0.05f || std::abs(p.z) > kHalf - 0.05f) continue;
      // Pixels whose view ray passes near the sphere show the sphere, not the ground.
      if (ray_clearance(ray.origin, ray.direction, glm::length(p - ray.origin)) < kSphereRadius * 1.1f)
        continue;
      trace::LightSample ls;
      if (!trace::sample_punctual(light, p, ls)) continue;
      // Local frame of the ground: z = +y.
      auto local = [](const glm::vec3& w) { return glm::vec3(w.x, -w.z, w.y); };
      const glm::vec3 expected =
          bsdf.eval(local(-ray.direction), local(ls.wi)) * ls.wi.y * ls.radiance;
      const glm::vec3 got = out.views[0].linear[std::size_t(y) * size + std::size_t(x)];
      tally.add(got, expected, ray_clearance(p, ls.wi, std::min(ls.distance, 100.0f)),
                kSphereRadius);
    }
  std::printf("%s: %d lit pixels (worst relative error %.4f), %d in shadow\n", c.name.c_str(),
              tally.lit, tally.worst, tally.shadowed);
  // Enough pixels of each kind for the checks to mean something.
  EXPECT_GT(tally.lit, 1500) << c.name;
  EXPECT_GT(tally.shadowed, 15) << c.name;
  EXPECT_EQ(tally.lit_bad, 0) << c.name << ": lit pixels off by > 3 %, worst " << tally.worst;
  EXPECT_EQ(tally.shadow_bad, 0) << c.name << ": shadowed pixels with light leaking in";
}

INSTANTIATE_TEST_SUITE_P(Lights, DirectLightTest, ::testing::Values(0, 1, 2),
                         [](const ::testing::TestParamInfo<int>& i) { return make_case(i.param).name; });

}  // namespace
}  // namespace ddish::raster::test
