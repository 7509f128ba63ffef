// The visibility pass (raster/visibility_pass.h) against the forward pass: the same scene with
// overdraw, alpha-masked quads cut and kept, a blended quad, a spot light with shadows and
// probe light, seen by three views at MSAA 4 and 1, must give the same image (textured scenes
// differ a little more: the forward pass takes texture gradients and the normal's variance
// from its 2x2 pixel quad, the visibility pass from the next pixel's barycentrics; Sponza and
// the Breakfast room measured 55 and 59 dB, README "Shading pass"). Every view method must
// give the same pixels, and the renderer picks the pass as RendererOptions::shading_pass says.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <span>
#include <vector>

#include "../gpu/gpu_test.h"
#include "gpu/error.h"
#include "raster/renderer.h"
#include "raster/visibility_pass.h"
#include "raster_scenes.h"
#include "scene/view.h"

namespace ddish::raster::test {
namespace {

using gpu::test::GpuTest;

class VisibilityPassTest : public GpuTest {
 protected:
  // Whether this device runs the visibility pass (Mesa 22's lavapipe does not).
  bool supported(const scene::Scene& s, const probes::ProbeVolume& volume) {
    try {
      Renderer r(device(), s, volume, {.msaa = 1, .shading_pass = ShadingPass::visibility});
      return true;
    } catch (const gpu::GpuError&) {
      return false;
    }
  }
};

std::vector<scene::View> three_views(int size) {
  std::vector<scene::View> views;
  for (float x : {-0.3f, 0.2f, 0.6f})
    views.push_back(scene::look_at_view({x, 3.0f, 3.2f}, {0, 0.6f, 0}, {0, 1, 0}, 0.9f, size, size));
  return views;
}

// PSNR of the display pixels (8-bit sRGB, R, G and B) of b against a, over all views.
double display_psnr(const FrameOutput& a, const FrameOutput& b) {
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t v = 0; v < a.views.size(); ++v)
    for (std::size_t i = 0; i < a.views[v].display.size(); ++i)
      for (int c = 0; c < 3; ++c) {
        const double d = double((a.views[v].display[i] >> (8 * c)) & 0xffu) -
                         double((b.views[v].display[i] >> (8 * c)) & 0xffu);
        sum += d * d;
        ++n;
      }
  const double mse = sum / double(n);
  return mse == 0.0 ? INFINITY : 10.0 * std::log10(255.0 * 255.0 / mse);
}

TEST_F(VisibilityPassTest, SameImageAsTheForwardPass) {
  const scene::Scene blended = overdraw_scene();
  const probes::ProbeVolume volume = lit_volume(blended);
  if (!supported(blended, volume)) GTEST_SKIP() << "no visibility pass on " << device().info().name;
  // Without its BLEND quad (made opaque) the scene takes the other way out of the shading:
  // straight into the resolve image, with no multisampled colour (VisibilityPassDesc::
  // shade_resolved); with it, into the multisampled colour that the quad blends over.
  scene::Scene opaque = blended;
  for (scene::Material& m : opaque.materials)
    if (m.alpha_mode == scene::AlphaMode::Blend) m.alpha_mode = scene::AlphaMode::Opaque;
  const std::vector<scene::View> views = three_views(40);
  for (const scene::Scene* s : {&blended, static_cast<const scene::Scene*>(&opaque)})
    for (std::uint32_t msaa : {4u, 1u}) {
      Renderer forward(device(), *s, volume, {.msaa = msaa, .shading_pass = ShadingPass::forward});
      Renderer visibility(device(), *s, volume, {.msaa = msaa, .shading_pass = ShadingPass::visibility});
      ASSERT_EQ(visibility.shading_pass(), ShadingPass::visibility);
      ASSERT_EQ(visibility.plan().alpha_blend, s == &blended);
      const FrameOutput a = forward.render(*s, views);
      const FrameOutput b = visibility.render(*s, views);
      ASSERT_EQ(b.views.size(), views.size());
      const double psnr = display_psnr(a, b);
      // Measured on lavapipe 25: 73.5 dB at MSAA 4 with the blended quad and 73.6 dB without
      // (edge pixels: the same shadings, averaged in the shader before the fp16 target instead
      // of by the resolve after it, and one shading for the sphere's inner edges: 78.3 dB when
      // each triangle was shaded) and identical display pixels at MSAA 1. The scene is
      // untextured, so the gradients cannot differ.
      EXPECT_GT(psnr, 60.0) << "MSAA " << msaa << (s == &blended ? ", blended quad" : ", opaque");
      std::printf("visibility against forward, MSAA %u, %s: %.2f dB\n", msaa,
                  s == &blended ? "blended quad" : "opaque", psnr);
    }
}

// The largest difference of one display channel (8-bit sRGB) between a and b, over all views.
int max_display_difference(const FrameOutput& a, const FrameOutput& b) {
  int most = 0;
  for (std::size_t v = 0; v < a.views.size(); ++v)
    for (std::size_t i = 0; i < a.views[v].display.size(); ++i)
      for (int c = 0; c < 3; ++c) {
        const int d = int((a.views[v].display[i] >> (8 * c)) & 0xffu) - int((b.views[v].display[i] >> (8 * c)) & 0xffu);
        most = std::max(most, std::abs(d));
      }
  return most;
}

// A ridge roof along x: two faces at 90 degrees that share the ridge's vertices (whose normals
// are the faces' mean): one surface to continues(), which looks at indices, not at angles.
scene::Mesh ridge_roof() {
  scene::Mesh m;
  m.name = "roof";
  const float r = std::sqrt(0.5f);
  m.positions = {{-1, 0.5f, 0}, {1, 0.5f, 0}, {-1, 0, 0.5f}, {1, 0, 0.5f}, {-1, 0, -0.5f}, {1, 0, -0.5f}};
  m.normals = {{0, 1, 0}, {0, 1, 0}, {0, r, r}, {0, r, r}, {0, r, -r}, {0, r, -r}};
  m.indices = {0, 2, 3, 0, 3, 1, 0, 1, 5, 0, 5, 4};  // counter-clockwise from above
  for (const glm::vec3& p : m.positions) m.bounds.expand(p);
  return m;
}

// A flat 2 x 1 m strip in y = 0 of two quads, red and blue by vertex colour, whose vertices on
// the seam at x = 0 are duplicated (as a file holds a colour or UV seam): no vertex in common.
scene::Mesh seamed_strip() {
  scene::Mesh m;
  m.name = "strip";
  for (int side = 0; side < 2; ++side) {
    const float x0 = side == 0 ? -1.0f : 0.0f;
    const glm::vec4 colour = side == 0 ? glm::vec4(1, 0, 0, 1) : glm::vec4(0, 0, 1, 1);
    const auto first = static_cast<std::uint32_t>(m.positions.size());
    for (glm::vec3 p : {glm::vec3(x0, 0, -0.5f), glm::vec3(x0, 0, 0.5f), glm::vec3(x0 + 1, 0, 0.5f),
                        glm::vec3(x0 + 1, 0, -0.5f)}) {
      m.positions.push_back(p);
      m.normals.push_back({0, 1, 0});
      m.colors.push_back(colour);
    }
    m.indices.insert(m.indices.end(), {first, first + 1, first + 2, first, first + 2, first + 3});
  }
  for (const glm::vec3& p : m.positions) m.bounds.expand(p);
  return m;
}

// Where the samples of an MSAA pixel fall on two triangles of one surface, the pixel is shaded
// once (visibility_shade.glsl's continues()); where the surface's attributes jump (the strip's
// colour seam, whose vertices are duplicated) each triangle is still shaded on its own, so the
// pixels stay close to the forward pass's. Measured on lavapipe 25: at most 4 levels apart (the
// sphere's inner edges and the roof's ridge, one shading where the forward pass averages two or
// three), 1 when every triangle is shaded on its own, 183 when the seam's triangles join too.
// The ridge folds by 90 degrees but shares its vertices, so its normals are continuous and one
// shading extrapolated across it is as close as the sphere's.
TEST_F(VisibilityPassTest, OneShadingPerSurfaceButNotAcrossSeams) {
  scene::Scene s = one_mesh_scene(ridge_roof(), make_material({0.8f, 0.8f, 0.8f}, 0.0f, 0.7f));
  add_instance(s, seamed_strip(), make_material({1.0f, 1.0f, 1.0f}, 0.0f, 0.7f), {0.0f, 0.0f, 1.5f});
  add_instance(s, uv_sphere(0.4f, 48, 24), make_material({0.7f, 0.7f, 0.7f}, 0.0f, 0.5f), {0.0f, 0.6f, -1.4f});
  scene::Light sun;
  sun.name = "sun";
  sun.type = scene::LightType::Directional;
  sun.intensity = 3.0f;
  add_light(s, sun, {0.0f, 3.0f, 3.0f}, {0.0f, -0.4f, -1.0f});  // lights the roof's +z face
  const probes::ProbeVolume volume = lit_volume(s);
  if (!supported(s, volume)) GTEST_SKIP() << "no visibility pass on " << device().info().name;
  std::vector<scene::View> views;
  for (float x : {-1.2f, 0.7f})
    views.push_back(scene::look_at_view({x, 2.5f, 2.8f}, {0, 0.3f, 0}, {0, 1, 0}, 0.9f, 64, 64));
  Renderer forward(device(), s, volume, {.msaa = 4, .shading_pass = ShadingPass::forward});
  Renderer visibility(device(), s, volume, {.msaa = 4, .shading_pass = ShadingPass::visibility});
  const FrameOutput a = forward.render(s, views);
  const FrameOutput b = visibility.render(s, views);
  const int most = max_display_difference(a, b);
  std::printf("visibility against forward, MSAA 4: at most %d levels apart\n", most);
  EXPECT_LE(most, 8);
}

TEST_F(VisibilityPassTest, EveryViewMethodGivesTheSamePixels) {
  const scene::Scene s = overdraw_scene();
  const probes::ProbeVolume volume = lit_volume(s);
  if (!supported(s, volume)) GTEST_SKIP() << "no visibility pass on " << device().info().name;
  const std::vector<scene::View> views = three_views(32);
  Renderer per_view(device(), s, volume, {.shading_pass = ShadingPass::visibility});
  const FrameOutput reference = per_view.render(s, views);
  for (ViewMethod method : {ViewMethod::layered, ViewMethod::multiview}) {
    if (method == ViewMethod::layered && !device().features().shader_output_layer) continue;
    Renderer r(device(), s, volume, {.view_method = method, .shading_pass = ShadingPass::visibility});
    const FrameOutput out = r.render(s, views);
    for (std::size_t v = 0; v < views.size(); ++v)
      EXPECT_EQ(out.views[v].linear, reference.views[v].linear) << to_string(method) << " view " << v;
  }
}

TEST_F(VisibilityPassTest, ChosenWhereTheDeviceHasItUnlessTheForwardPassIsAskedFor) {
  const scene::Scene s = overdraw_scene();
  const probes::ProbeVolume volume = lit_volume(s);
  const bool has = supported(s, volume);
  const ShadingPass automatic = has ? ShadingPass::visibility : ShadingPass::forward;
  EXPECT_EQ(Renderer(device(), s, volume, {.msaa = 1}).shading_pass(), automatic);
  // The trivial floor is always the forward pass; the depth prepass is the forward pass's.
  EXPECT_EQ(Renderer(device(), s, volume, {.msaa = 1, .shading = Shading::trivial}).shading_pass(),
            ShadingPass::forward);
  EXPECT_EQ(Renderer(device(), s, volume, {.msaa = 1, .depth_prepass = false}).shading_pass(),
            ShadingPass::forward);
  EXPECT_THROW(Renderer(device(), s, volume,
                        {.msaa = 1, .depth_prepass = true, .shading_pass = ShadingPass::visibility}),
               gpu::GpuError);
  if (device().features().sample_rate_shading) {
    EXPECT_EQ(Renderer(device(), s, volume, {.msaa = 1, .sample_shading = true}).shading_pass(),
              ShadingPass::forward);
    EXPECT_THROW(Renderer(device(), s, volume,
                          {.msaa = 1, .sample_shading = true, .shading_pass = ShadingPass::visibility}),
                 gpu::GpuError);
  }
}

}  // namespace
}  // namespace ddish::raster::test
