// RendererOptions::shading = trivial (raster/shading.h), the fill-rate floor of the benchmarks:
// the same triangles in the same passes, a constant colour where a triangle covers the pixel
// centre and the environment everywhere else, nothing in between (MSAA 1).
#include <gtest/gtest.h>

#include <span>

#include "../gpu/gpu_test.h"
#include "probes/probe_grid.h"
#include "probes/probe_volume.h"
#include "raster/renderer.h"
#include "raster_scenes.h"
#include "scene/view.h"

namespace ddish::raster::test {
namespace {

using gpu::test::GpuTest;

class TrivialShadingTest : public GpuTest {};

TEST(Shading, NamesRoundTrip) {
  for (Shading s : {Shading::full, Shading::trivial}) EXPECT_EQ(parse_shading(to_string(s)), s);
  EXPECT_FALSE(parse_shading("flat"));
}

TEST_F(TrivialShadingTest, ConstantColourOnGeometryEnvironmentElsewhere) {
  const float radius = 0.5f;
  scene::Scene s = one_mesh_scene(uv_sphere(radius, 48, 24), make_material({0.8f, 0.2f, 0.2f}, 0.0f, 0.5f));
  s.sidecar.environment = {0.0625f, 0.125f, 0.25f};  // exact in the RGBA16F target
  const probes::ProbeVolume volume(probes::ProbeGrid(s.bounds(), {2, 2, 2}));
  const int size = 32;
  const scene::View view = scene::look_at_view({0, 0, 3}, {0, 0, 0}, {0, 1, 0}, 0.6f, size, size);

  Renderer trivial(device(), s, volume, {.msaa = 1, .shading = Shading::trivial});
  Renderer full(device(), s, volume, {.msaa = 1});
  const FrameOutput out = trivial.render(s, std::span(&view, 1));
  const FrameOutput ref = full.render(s, std::span(&view, 1));
  ASSERT_EQ(out.views.size(), 1u);
  EXPECT_EQ(out.stats.forward_passes, ref.stats.forward_passes);
  EXPECT_EQ(out.stats.cull.triangles_drawn, ref.stats.cull.triangles_drawn);

  int hit = 0, miss = 0, other = 0, disagree = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const glm::vec3 got = out.views[0].linear[static_cast<std::size_t>(y * size + x)];
      const bool is_colour = got == kTrivialColor;
      const bool is_environment = got == s.environment();
      if (!is_colour && !is_environment) ++other;
      // The full shading's coverage is the same (its lit sphere is never the environment).
      const glm::vec3 shaded = ref.views[0].linear[static_cast<std::size_t>(y * size + x)];
      if (is_colour != (shaded != s.environment())) ++disagree;
      // Away from the tessellated silhouette, the analytic sphere says which it must be.
      const scene::Ray ray = scene::view_ray(view, float(x) + 0.5f, float(y) + 0.5f);
      const glm::vec3 d = glm::normalize(ray.direction);
      const float miss_distance = glm::length(ray.origin - glm::dot(ray.origin, d) * d);
      if (miss_distance < 0.9f * radius) {
        ++hit;
        EXPECT_TRUE(is_colour) << "pixel " << x << "," << y;
      } else if (miss_distance > 1.05f * radius) {
        ++miss;
        EXPECT_TRUE(is_environment) << "pixel " << x << "," << y;
      }
    }
  EXPECT_EQ(other, 0) << "pixels that are neither the constant colour nor the environment";
  EXPECT_EQ(disagree, 0) << "pixels where trivial and full shading cover differently";
  EXPECT_GT(hit, 100);
  EXPECT_GT(miss, 100);
}

}  // namespace
}  // namespace ddish::raster::test
