// RendererOptions::depth_prepass (raster/forward_pass.h): depth first, then shading that skips
// the lighting of fragments hidden at every sample. It must not change a pixel: the same scene,
// with overdraw, alpha-masked quads cut and kept, a blended quad and probe light, is rendered
// with and without it at MSAA 4 and 1 and compared pixel by pixel.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <span>

#include "../gpu/gpu_test.h"
#include "gpu/error.h"
#include "probes/probe_grid.h"
#include "probes/probe_volume.h"
#include "raster/renderer.h"
#include "raster_scenes.h"
#include "scene/view.h"

namespace ddish::raster::test {
namespace {

using gpu::test::GpuTest;

class DepthPrepassTest : public GpuTest {};

scene::Material masked(const glm::vec3& base, float alpha) {
  scene::Material m = make_material(base, 0.0f, 0.6f);
  m.base_color.a = alpha;
  m.alpha_mode = scene::AlphaMode::Mask;
  m.alpha_cutoff = 0.5f;
  m.double_sided = true;
  return m;
}

// A ground under a sphere, two masked quads above it (one below its cutoff: cut out, one above:
// kept), a blended quad, a spot light and probes with a constant and a linear SH term.
scene::Scene overdraw_scene() {
  scene::Scene s = sphere_over_ground(0.4f);
  add_instance(s, ground_quad(0.4f), masked({0.2f, 0.6f, 0.2f}, 0.3f), {0.0f, 1.4f, 0.0f});
  add_instance(s, ground_quad(0.4f), masked({0.2f, 0.2f, 0.7f}, 0.9f), {0.5f, 1.2f, 0.5f});
  scene::Material glass = make_material({0.9f, 0.8f, 0.3f}, 0.0f, 0.2f);
  glass.base_color.a = 0.5f;
  glass.alpha_mode = scene::AlphaMode::Blend;
  add_instance(s, ground_quad(0.3f), glass, {-0.5f, 1.0f, 0.4f});
  scene::Light spot;
  spot.name = "spot";
  spot.type = scene::LightType::Spot;
  spot.intensity = 10.0f;
  add_light(s, spot, {0.3f, 2.5f, 0.2f}, {0.0f, -1.0f, 0.0f});
  s.sidecar.environment = {0.0625f, 0.125f, 0.25f};
  return s;
}

probes::ProbeVolume lit_volume(const scene::Scene& s) {
  probes::ProbeVolume volume(probes::ProbeGrid(s.bounds(), {3, 3, 3}), 2);
  sh::ShRgb sh(2);
  sh[0] = glm::vec3(0.8f, 1.0f, 1.2f);
  sh[1] = glm::vec3(0.3f, 0.2f, 0.1f);
  for (std::uint32_t i = 0; i < volume.probe_count(); ++i) volume.set_sh(i, sh);
  return volume;
}

TEST_F(DepthPrepassTest, SamePixelsWithAndWithout) {
  if (!device().features().post_depth_coverage) GTEST_SKIP() << "no VK_EXT_post_depth_coverage";
  const scene::Scene s = overdraw_scene();
  const probes::ProbeVolume volume = lit_volume(s);
  const int size = 48;
  const scene::View view = scene::look_at_view({0.2f, 3.0f, 3.2f}, {0, 0.6f, 0}, {0, 1, 0}, 0.9f, size, size);
  for (std::uint32_t msaa : {4u, 1u}) {
    Renderer with(device(), s, volume, {.msaa = msaa, .depth_prepass = true});
    Renderer without(device(), s, volume, {.msaa = msaa, .depth_prepass = false});
    ASSERT_TRUE(with.depth_prepass());
    ASSERT_FALSE(without.depth_prepass());
    const FrameOutput a = with.render(s, std::span(&view, 1));
    const FrameOutput b = without.render(s, std::span(&view, 1));
    ASSERT_EQ(a.views.size(), 1u);
    float worst = 0.0f;
    int lit = 0;
    for (std::size_t i = 0; i < a.views[0].linear.size(); ++i) {
      const glm::vec3 d = glm::abs(a.views[0].linear[i] - b.views[0].linear[i]);
      worst = std::max(worst, std::max(d.x, std::max(d.y, d.z)));
      if (b.views[0].linear[i] != s.environment()) ++lit;
    }
    // The same shader code on the same inputs: equal to the last bit.
    EXPECT_EQ(worst, 0.0f) << "MSAA " << msaa;
    EXPECT_GT(lit, size * size / 2) << "MSAA " << msaa;  // the scene fills the view
  }
}

TEST_F(DepthPrepassTest, AutomaticWhereTheDeviceHasPostDepthCoverage) {
  const scene::Scene s = overdraw_scene();
  const probes::ProbeVolume volume = lit_volume(s);
  const bool has = device().features().post_depth_coverage;
  EXPECT_EQ(Renderer(device(), s, volume, {}).depth_prepass(), has);
  // The trivial floor is one pass whatever is asked.
  EXPECT_FALSE(Renderer(device(), s, volume, {.shading = Shading::trivial}).depth_prepass());
  if (!has) {
    EXPECT_THROW(Renderer(device(), s, volume, {.depth_prepass = true}), gpu::GpuError);
  }
}

}  // namespace
}  // namespace ddish::raster::test
