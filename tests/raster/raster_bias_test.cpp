// Fixed biases of the rasterizer against the path tracer that no probe setting changes
// (issue 8: the Breakfast room's RMSE was 1.114 at every probe setting, 1.126 direct only).
//
// 1. Specular aliasing of punctual lights on curved glossy surfaces. The path tracer's pixel is
//    the radiance averaged over the pixel's footprint (a Gaussian filter); the rasterizer shades
//    once per pixel. On a small, curved, low-roughness object under a directional light the
//    highlight is much narrower than a pixel, so a point sample near its peak overshoots the
//    footprint's average many times (or misses it): one teapot pixel read 183 against the
//    reference's 20, and that pixel alone was 99 % of the image's squared linear error (RMSE
//    1.114; 0.098 without it). surface_lighting.glsl widens the punctual lights' GGX lobe by the
//    screen-space variance of the normal (Tokuyoshi and Kaplanyan 2021).
// 2. Light leaking where a caster seen at grazing light meets the surface it shadows: the
//    shadow pass's slope-scaled depth bias pushed such casters back by several texels
//    (graphics_pipeline.cpp), so the Breakfast room's back wall let the sun through along the
//    side wall and the picture it touches.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "../gpu/gpu_test.h"
#include "probes/probe_grid.h"
#include "probes/probe_volume.h"
#include "raster/renderer.h"
#include "raster_scenes.h"
#include "scene/view.h"
#include "trace/reference.h"
#include "trace/tracer.h"

namespace ddish::raster::test {
namespace {

using gpu::test::GpuTest;

float luminance(const glm::vec3& c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

class RasterBiasTest : public GpuTest {};

TEST_F(RasterBiasTest, SunHighlightOnSmallGlossySphereMatchesPixelAverage) {
  scene::Scene s = one_mesh_scene(uv_sphere(0.1f, 96, 48), make_material({0.5f, 0.5f, 0.5f}, 0.35f, 0.2f));
  scene::Light sun;
  sun.name = "sun";
  sun.type = scene::LightType::Directional;
  sun.intensity = 8.0f;
  add_light(s, sun, {0.0f, 3.0f, 0.0f}, {-0.8f, -0.5f, 0.2f});

  trace::PathOptions paths;
  paths.max_bounces = 1;  // direct light only, what the rasterizer computes without probes
  const trace::Tracer tracer(s, paths);
  const probes::ProbeVolume volume(probes::ProbeGrid(s.bounds(), {2, 2, 2}));
  RendererOptions options;
  options.probes = false;
  Renderer renderer(device(), s, volume, options);

  const int size = 40;
  // The sphere spans about 13 and 8 pixels: a pixel covers 0.15 to 0.25 rad of its normals, as
  // on the teapot. Two sizes put the highlight's peak at different places within its pixel.
  for (const float fov_deg : {14.0f, 24.0f}) {
    const scene::View view = scene::look_at_view({0.3f, 0.2f, 2.5f}, {0.0f, 0.0f, 0.0f},
                                                 {0.0f, 1.0f, 0.0f}, glm::radians(fov_deg), size, size);
    trace::ReferenceOptions ro;
    ro.spp = 1024;
    ro.seed = 3;
    const trace::ReferenceImage ref = trace::render_reference(tracer, view, ro);
    const FrameOutput out = renderer.render(s, std::span(&view, 1));
    const std::vector<glm::vec3> img = out.views[0].linear.to_floats();
    ASSERT_EQ(img.size(), ref.pixels.size());

    std::size_t peak = 0;
    float ref_max = 0.0f, img_max = 0.0f;
    for (std::size_t i = 0; i < img.size(); ++i) {
      img_max = std::max(img_max, luminance(img[i]));
      if (luminance(ref.pixels[i]) > ref_max) {
        ref_max = luminance(ref.pixels[i]);
        peak = i;
      }
    }
    // The highlight's energy: a 5x5 window around the reference's peak (the pixel filter and
    // the rasterizer's footprint spread it differently, the window's sum not).
    const int px = int(peak % std::size_t(size)), py = int(peak / std::size_t(size));
    double ref_sum = 0.0, img_sum = 0.0;
    for (int y = std::max(0, py - 2); y <= std::min(size - 1, py + 2); ++y)
      for (int x = std::max(0, px - 2); x <= std::min(size - 1, px + 2); ++x) {
        const std::size_t i = std::size_t(y) * std::size_t(size) + std::size_t(x);
        ref_sum += luminance(ref.pixels[i]);
        img_sum += luminance(img[i]);
      }
    std::printf("fov %.0f: brightest pixel %.2f (reference %.2f at %d,%d); 5x5 sum %.2f (reference %.2f)\n",
                double(fov_deg), double(img_max), double(ref_max), px, py, img_sum, ref_sum);
    ASSERT_GT(ref_max, 2.0f) << "the view must see the sun's highlight";
    // Point-sampled, the peak lands in one pixel or between pixels: 5.3x the reference's
    // brightest pixel at 24 degrees, and the window's sum 42 % low at 14 degrees.
    EXPECT_LT(img_max, 2.0f * ref_max) << "fov " << fov_deg;
    EXPECT_NEAR(img_sum, ref_sum, 0.2 * ref_sum) << "fov " << fov_deg;
  }
}

// A quad with corners a, b, c, d (counter-clockwise seen from the side it faces).
scene::Mesh quad(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& d) {
  scene::Mesh m;
  m.name = "quad";
  m.positions = {a, b, c, d};
  m.normals.assign(4, glm::normalize(glm::cross(b - a, d - a)));
  m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  m.tangents.assign(4, glm::vec4(glm::normalize(b - a), 1.0f));
  m.indices = {0, 1, 2, 0, 2, 3};
  for (const glm::vec3& p : m.positions) m.bounds.expand(p);
  return m;
}

// Two walls meet at a corner; the sun comes from behind the back wall (which faces away from
// it, at 12 degrees from its plane) and the back wall shadows the whole side wall (the
// Breakfast room's back corner). Every pixel must be dark. With the slope-scaled bias (1.5)
// the side wall was lit along the corner: 48 pixels above 0.05, up to 0.645 (fully lit: 1.93);
// without it, none.
TEST_F(RasterBiasTest, ShadowedCornerDoesNotLeak) {
  const scene::Material white = make_material({0.9f, 0.9f, 0.9f}, 0.0f, 0.95f);
  // Back wall: z = 0, facing +z, x and y in [0, 12]. Side wall: x = 0, facing +x, z in [0, 2],
  // y in [0, 3].
  scene::Scene s = one_mesh_scene(quad({0, 0, 0}, {12, 0, 0}, {12, 12, 0}, {0, 12, 0}), white);
  add_instance(s, quad({0, 0, 2}, {0, 0, 0}, {0, 3, 0}, {0, 3, 2}), white, {0.0f, 0.0f, 0.0f});
  scene::Light sun;
  sun.name = "sun";
  sun.type = scene::LightType::Directional;
  sun.intensity = 8.0f;
  // Towards the sun: (0.84, 0.5, -0.21): the side wall's cosine is 0.84, the back wall's < 0;
  // from the side wall at z the path to the sun crosses the back wall within x = 4 z <= 8, at
  // a height of at most 3 + 2.4 z <= 8 (the back wall is 12 high).
  add_light(s, sun, {5.0f, 5.0f, -3.0f}, {-0.84f, -0.5f, 0.21f});

  const probes::ProbeVolume volume(probes::ProbeGrid(s.bounds(), {2, 2, 2}));
  RendererOptions options;
  options.probes = false;
  options.msaa = 1;  // every pixel's shading point lies on the surface it shows
  // Coarse texels (one cascade of 256^2 over the view) widen the band the bias affects to
  // several pixels.
  options.shadow_map_size = 256;
  options.cascades = 1;
  Renderer renderer(device(), s, volume, options);
  const int w = 64, h = 48;
  const scene::View view = scene::look_at_view({1.6f, 1.5f, 1.8f}, {0.0f, 1.4f, 0.0f},
                                               {0.0f, 1.0f, 0.0f}, glm::radians(60.0f), w, h);
  const FrameOutput out = renderer.render(s, std::span(&view, 1));
  float brightest = 0.0f;
  int lit = 0;
  for (const glm::vec3& c : out.views[0].linear) {
    brightest = std::max(brightest, luminance(c));
    if (luminance(c) > 0.05f) ++lit;
  }
  std::printf("shadowed corner: %d pixels above 0.05, brightest %.3f (a fully lit side-wall pixel: %.2f)\n",
              lit, double(brightest), 8.0 * 0.9 * 0.84 / 3.14159265);
  EXPECT_EQ(lit, 0);
}

}  // namespace
}  // namespace ddish::raster::test
