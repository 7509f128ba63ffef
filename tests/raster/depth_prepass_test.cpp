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
#include "probes/probe_volume.h"
#include "raster/renderer.h"
#include "raster_scenes.h"
#include "scene/view.h"

namespace ddish::raster::test {
namespace {

using gpu::test::GpuTest;

class DepthPrepassTest : public GpuTest {};

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
  // The prepass belongs to the forward pass, which shades by default only where the visibility
  // pass cannot (raster/shading_pass.h).
  EXPECT_EQ(Renderer(device(), s, volume, {.shading_pass = ShadingPass::forward}).depth_prepass(), has);
  const Renderer automatic(device(), s, volume, {});
  EXPECT_EQ(automatic.depth_prepass(), has && automatic.shading_pass() == ShadingPass::forward);
  // The trivial floor is one pass whatever is asked.
  EXPECT_FALSE(Renderer(device(), s, volume, {.shading = Shading::trivial}).depth_prepass());
  if (!has) {
    EXPECT_THROW(Renderer(device(), s, volume, {.depth_prepass = true}), gpu::GpuError);
  }
}

}  // namespace
}  // namespace ddish::raster::test
