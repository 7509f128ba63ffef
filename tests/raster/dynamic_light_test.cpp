// Lights that change between frames (scenes/cornell_light.gltf moves its point light on STEP keys
// and "switches it off" by moving it into a closed housing): the shadow maps kept while nothing
// moved must be redrawn when a light moves, a light inside a closed caster must light nothing,
// and an intensity change needs no new shadow maps but must still reach the shading.
#include <gtest/gtest.h>

#include <vector>

#include "../gpu/gpu_test.h"
#include "probes/probe_grid.h"
#include "probes/probe_volume.h"
#include "raster/renderer.h"
#include "raster_scenes.h"
#include "scene/animation.h"
#include "scene/scene.h"
#include "scene/view.h"

namespace ddish::raster::test {
namespace {

using gpu::test::GpuTest;

class DynamicLightTest : public GpuTest {};

constexpr int kSize = 33;  // the centre pixel sees the ground at the origin

// A ground quad with a sphere floating over it and a point light whose node steps from `a`
// (t < 1) to `b` (t >= 1), the way the bundled scene's light moves.
scene::Scene stepping_light_scene(const glm::vec3& a, const glm::vec3& b) {
  scene::Scene s = sphere_over_ground(0.9f);
  scene::Light lamp;
  lamp.name = "lamp";
  lamp.type = scene::LightType::Point;
  lamp.intensity = 8.0f;
  add_light(s, lamp, a, {0.0f, -1.0f, 0.0f});
  scene::AnimChannel ch;
  ch.node = s.lights[0].node;
  ch.path = scene::AnimPath::Translation;
  ch.interpolation = scene::Interpolation::Step;
  ch.times = {0.0f, 1.0f};
  ch.width = 3;
  ch.values = {a.x, a.y, a.z, b.x, b.y, b.z};
  s.animations.push_back({"step", {ch}});
  s.pose(0.0);
  return s;
}

scene::View centre_view() {
  return scene::look_at_view({0, 3.5f, 3.5f}, {0, 0, 0}, {0, 1, 0}, 0.8f, kSize, kSize);
}

glm::vec3 centre(const FrameOutput& f) { return f.views[0].linear[(kSize / 2) * kSize + kSize / 2]; }

TEST_F(DynamicLightTest, MovingLightRedrawsShadowMaps) {
  scene::Scene s = stepping_light_scene({1.0f, 1.5f, 0.0f}, {-1.0f, 1.5f, 0.0f});
  const probes::ProbeVolume volume(probes::ProbeGrid(s.bounds(), {2, 2, 2}));
  Renderer renderer(device(), s, volume, {.msaa = 1, .probes = false});
  const scene::View view = centre_view();
  const FrameOutput first = renderer.render(s, std::span(&view, 1));
  EXPECT_EQ(first.stats.shadow_passes, 6u);  // a point light: six cube faces
  EXPECT_FALSE(first.stats.shadows_reused);
  // Posed again before the key: nothing moved, the maps are kept.
  EXPECT_TRUE(s.pose(0.5).empty());
  const FrameOutput still = renderer.render(s, std::span(&view, 1));
  EXPECT_TRUE(still.stats.shadows_reused);
  EXPECT_EQ(still.stats.shadow_passes, 0u);
  EXPECT_EQ(still.views[0].linear, first.views[0].linear);
  // After the key the light has jumped while no instance moved: the maps are redrawn and the
  // image is the one of a renderer that only ever saw the new place.
  EXPECT_TRUE(s.pose(1.0).empty());
  EXPECT_NEAR(s.lights[0].position.x, -1.0f, 1e-6f);
  const FrameOutput jumped = renderer.render(s, std::span(&view, 1));
  EXPECT_FALSE(jumped.stats.shadows_reused);
  EXPECT_EQ(jumped.stats.shadow_passes, 6u);
  EXPECT_NE(jumped.views[0].linear, first.views[0].linear);
  Renderer fresh(device(), s, volume, {.msaa = 1, .probes = false});
  EXPECT_EQ(fresh.render(s, std::span(&view, 1)).views[0].linear, jumped.views[0].linear);
  // And back (a renderer reused across a jump and back draws what it drew first).
  s.pose(0.0);
  const FrameOutput back = renderer.render(s, std::span(&view, 1));
  EXPECT_FALSE(back.stats.shadows_reused);
  EXPECT_EQ(back.views[0].linear, first.views[0].linear);
}

// "Off" as the bundled scene does it: the light steps inside a closed solid (a sphere around it,
// outward faces; shadow passes cull nothing), and the ground goes dark; stepping out lights it.
TEST_F(DynamicLightTest, LightInsideClosedCasterLightsNothing) {
  const glm::vec3 housing(1.2f, 1.5f, -1.2f);
  scene::Scene s = stepping_light_scene({0.8f, 1.5f, 0.5f}, housing);  // A: clear of the sphere
  add_instance(s, uv_sphere(0.25f, 24, 12), make_material({0.2f, 0.2f, 0.2f}, 0.0f, 0.9f), housing);
  s.pose(0.0);
  const probes::ProbeVolume volume(probes::ProbeGrid(s.bounds(), {2, 2, 2}));
  Renderer renderer(device(), s, volume, {.msaa = 1, .probes = false});
  const scene::View view = centre_view();
  const glm::vec3 on = centre(renderer.render(s, std::span(&view, 1)));
  EXPECT_GT(on.r, 0.1f);
  s.pose(1.0);
  const FrameOutput off = renderer.render(s, std::span(&view, 1));
  EXPECT_FALSE(off.stats.shadows_reused);
  EXPECT_LT(centre(off).r, 1e-4f) << "light leaks out of the closed housing";
  EXPECT_LT(centre(off).g, 1e-4f);
}

// Intensity is shading data, not shadow data: the maps are kept, the image follows the change.
TEST_F(DynamicLightTest, IntensityChangeKeepsShadowMapsAndReachesShading) {
  scene::Scene s = stepping_light_scene({0.5f, 1.5f, 0.5f}, {0.5f, 1.5f, 0.5f});
  const probes::ProbeVolume volume(probes::ProbeGrid(s.bounds(), {2, 2, 2}));
  Renderer renderer(device(), s, volume, {.msaa = 1, .probes = false});
  const scene::View view = centre_view();
  const glm::vec3 base = centre(renderer.render(s, std::span(&view, 1)));
  ASSERT_GT(base.r, 0.01f);
  s.lights[0].intensity *= 2.0f;
  const FrameOutput brighter = renderer.render(s, std::span(&view, 1));
  EXPECT_TRUE(brighter.stats.shadows_reused);
  EXPECT_NEAR(centre(brighter).r, 2.0f * base.r, 0.01f * base.r + 1e-3f);
  s.lights[0].intensity = 0.0f;
  const FrameOutput dark = renderer.render(s, std::span(&view, 1));
  EXPECT_TRUE(dark.stats.shadows_reused);
  EXPECT_LT(centre(dark).r, 1e-5f);
}

}  // namespace
}  // namespace ddish::raster::test
