// Stiff and extreme cases of the rasterizer (docs/extreme-cases.md), on lavapipe with
// validation: probes whose SH rings strongly negative next to a 1e6 emitter (no negative or NaN
// pixel: the shader clamps), probe values beyond fp16 (clamped to 65504 and counted), roughness
// exactly 0 and 1 and grazing views on a sphere, zero-area triangles, every probe inactive,
// a 64^3 L2 volume on the GPU, and shadow maps at 1e-3 and 1e4 metre scale.
// Already covered: ProbeUploadTest.ValuesBeyondFp16AreClampedAndCounted (the counter per
// value), ProbeLightingTest.InactiveProbesAreWeightedOut (all-inactive volume in the shader).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "probe_lighting_harness.h"
#include "probe_test_util.h"
#include "probes/probe_grid.h"
#include "probes/probe_volume.h"
#include "raster/brdf_dfg.h"
#include "raster/renderer.h"
#include "raster_scenes.h"
#include "scene/view.h"
#include "sh/convolution.h"
#include "sh/sh_rgb.h"
#include "trace/bsdf.h"
#include "trace/lights.h"
#include "trace/specular_albedo.h"

namespace ddish::raster::test {
namespace {

constexpr int kSize = 48;

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Every probe of a 3^3 volume around the scene holds `sh`.
probes::ProbeVolume uniform_volume(const scene::Scene& s, const sh::ShRgb& sh) {
  scene::Aabb box = s.bounds();
  box.min -= glm::vec3(0.5f);
  box.max += glm::vec3(0.5f);
  probes::ProbeVolume volume(probes::ProbeGrid(box, {3, 3, 3}), 2);
  for (std::uint32_t i = 0; i < volume.probe_count(); ++i) volume.set_sh(i, sh);
  return volume;
}

scene::View front_view(float distance = 3.0f) {
  return scene::look_at_view({0.0f, 0.0f, distance}, {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f},
                             glm::radians(45.0f), kSize, kSize);
}

// The unit sphere's point and n.v seen through pixel (x, y); false off the sphere.
bool sphere_hit(const scene::View& view, int x, int y, glm::vec3& normal, float& n_dot_v) {
  const scene::Ray ray = scene::view_ray(view, float(x) + 0.5f, float(y) + 0.5f);
  const float b = glm::dot(ray.origin, ray.direction);
  const float disc = b * b - (glm::dot(ray.origin, ray.origin) - 1.0f);
  if (disc <= 0.0f) return false;
  normal = glm::normalize(ray.origin + ray.direction * (-b - std::sqrt(disc)));
  n_dot_v = glm::dot(normal, -ray.direction);
  return true;
}

// The SH of a 0.1 rad cap of radiance `radiance` around `axis`: its Funk-Hecke factors
// z_l = 2 pi integral_c^1 P_l(mu) dmu, c = cos 0.1, times Y_lm(axis).
sh::ShRgb bright_cap(const glm::vec3& axis, float radiance) {
  const double c = std::cos(0.1);
  const double z[3] = {2.0 * kTestPi * (1.0 - c), kTestPi * (1.0 - c * c), kTestPi * (c - c * c * c)};
  float y[9];
  sh::eval_basis(axis, 2, y);
  sh::ShRgb s(2);
  for (int i = 0; i < 9; ++i) s[i] = glm::vec3(radiance * float(z[sh::band_of(i)]) * y[i]);
  return s;
}

class ExtremeRasterTest : public ProbeGpuTest {};

// A diffuse sphere lit only by probes that hold a 1e6-radiance cap (L0 8.9e3, L1 1.5e4: within
// fp16) seen from the side: the L2 irradiance of such a point-like source rings to -0.04 of its
// power on the far side (extreme_sh_test.cpp). The shader clamps irradiance to >= 0, so no
// pixel is negative or NaN, the pixels whose raw irradiance is clearly negative are exactly 0,
// and those facing the emitter match albedo (1 - E(n.v)) E_raw / pi within 2 % (fp16
// coefficients, as in constant_probe_test.cpp).
TEST_F(ExtremeRasterTest, NegativeRingingIsClampedToZeroNeverNegativeOrNaN) {
  const glm::vec3 albedo(0.5f);
  scene::Scene s = one_mesh_scene(uv_sphere(1.0f, 64, 32), make_material(albedo, 0.0f, 0.9f));
  const glm::vec3 axis(1.0f, 0.0f, 0.0f);  // the emitter to the right of the view
  const sh::ShRgb ringing = bright_cap(axis, 1e6f);
  ASSERT_LT(sh::max_abs(ringing), sh::kHalfMax);
  const probes::ProbeVolume volume = uniform_volume(s, ringing);
  RendererOptions options;
  options.msaa = 1;
  Renderer renderer(device(), s, volume, options);
  EXPECT_EQ(renderer.upload_probes(volume).clamps.overflowed, 0u);
  const scene::View view = front_view();
  const FrameOutput out = renderer.render(s, std::span(&view, 1));
  const auto& table = trace::DielectricSpecularAlbedo::get();
  int negative_raw = 0, zero_there = 0, facing = 0, facing_ok = 0;
  float min_pixel = std::numeric_limits<float>::max();
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const glm::vec3 got = out.views[0].linear[std::size_t(y) * kSize + std::size_t(x)];
      ASSERT_TRUE(finite(got)) << x << "," << y;
      min_pixel = std::min({min_pixel, got.x, got.y, got.z});
      glm::vec3 n;
      float nov = 0.0f;
      if (!sphere_hit(view, x, y, n, nov) || nov < 0.2f) continue;
      const float raw = sh::irradiance(ringing, n).x;
      const float power = sh::max_abs(ringing);  // a scale for "clearly"
      if (raw < -0.02f * power) {
        ++negative_raw;
        if (got.x == 0.0f) ++zero_there;
      } else if (raw > 0.2f * power) {
        ++facing;
        const float want = albedo.x * (1.0f - table.directional(nov, 0.9f)) * raw / kTestPi;
        if (std::abs(got.x - want) < 0.02f * want) ++facing_ok;
      }
    }
  std::printf("[extreme] ringing probe: min pixel %g; %d pixels with negative raw irradiance "
              "(%d rendered 0), %d facing the emitter (%d within 2 %%)\n",
              double(min_pixel), negative_raw, zero_there, facing, facing_ok);
  EXPECT_GE(min_pixel, 0.0f);
  EXPECT_GT(negative_raw, 50);
  EXPECT_EQ(zero_there, negative_raw);
  EXPECT_GT(facing, 50);
  EXPECT_EQ(facing_ok, facing);
}

// Probes holding a uniform sky of radiance 1e6 (L0 = 3.5e6, 54 times fp16's largest value):
// ProbeTextures saturates L0 to 65504 and counts it (27 probes x 3 channels = 81 values a
// full upload), never writes Inf; the sphere renders finite, non-negative and no brighter than
// the saturated radiance 65504 / sqrt(4 pi) = 18478 reflected by albedo 0.5: 9239.
TEST_F(ExtremeRasterTest, ProbeValuesBeyondFp16AreClampedCountedAndRenderFinite) {
  scene::Scene s = one_mesh_scene(uv_sphere(1.0f, 32, 16), make_material(glm::vec3(0.5f), 0.0f, 0.9f));
  sh::ShRgb sky(2);
  sky[0] = glm::vec3(1e6f * std::sqrt(4.0f * kTestPi));
  const probes::ProbeVolume volume = uniform_volume(s, sky);
  RendererOptions options;
  options.msaa = 1;
  Renderer renderer(device(), s, volume, options);
  const ProbeUploadStats stats = renderer.upload_probes(volume);
  EXPECT_EQ(stats.clamps.overflowed, 27u * 3u);
  EXPECT_EQ(stats.clamps.not_finite, 0u);
  const scene::View view = front_view();
  const FrameOutput out = renderer.render(s, std::span(&view, 1));
  const float bound = 0.5f * 65504.0f / std::sqrt(4.0f * kTestPi);
  float max_pixel = 0.0f;
  for (const glm::vec3& p : out.views[0].linear) {
    ASSERT_TRUE(finite(p));
    EXPECT_GE(std::min({p.x, p.y, p.z}), 0.0f);
    max_pixel = std::max({max_pixel, p.x, p.y, p.z});
  }
  std::printf("[extreme] 1e6 sky: brightest pixel %g (bound %g)\n", double(max_pixel), double(bound));
  EXPECT_GT(max_pixel, 0.5f * bound);
  EXPECT_LE(max_pixel, bound * 1.001f);
}

// Metal spheres of roughness exactly 0 and exactly 1 under a constant probe radiance L: every
// pixel finite and non-negative, silhouette (n.v -> 0, grazing) included, and pixels with
// n.v >= 0.2 equal to the split-sum (F0 A + B) L within 2 %, as at roughness 0.3
// (constant_probe_test.cpp).
TEST_F(ExtremeRasterTest, RoughnessZeroAndOneSpheresMatchSplitSumAndStayFiniteAtGrazing) {
  const glm::vec3 base(0.95f, 0.64f, 0.54f), radiance(0.8f, 1.1f, 1.4f);
  for (float roughness : {0.0f, 1.0f}) {
    scene::Scene s = one_mesh_scene(uv_sphere(1.0f, 96, 48), make_material(base, 1.0f, roughness));
    sh::ShRgb constant(2);
    constant[0] = radiance * std::sqrt(4.0f * kTestPi);
    const probes::ProbeVolume volume = uniform_volume(s, constant);
    RendererOptions options;
    options.msaa = 1;
    Renderer renderer(device(), s, volume, options);
    const scene::View view = front_view();
    const FrameOutput out = renderer.render(s, std::span(&view, 1));
    // The split-sum factors on 161 nodes of n.v over [0.2, 1], linearly interpolated (their
    // curvature keeps that within 1e-4), instead of integrating per pixel.
    std::vector<glm::vec2> dfg;
    for (int j = 0; j <= 160; ++j) dfg.push_back(integrate_dfg(0.2f + 0.8f * float(j) / 160.0f, roughness, 256));
    auto split_sum = [&](float nov) {
      const float t = std::clamp((nov - 0.2f) / 0.8f * 160.0f, 0.0f, 160.0f);
      const int j = std::min(int(t), 159);
      return glm::mix(dfg[std::size_t(j)], dfg[std::size_t(j) + 1], t - float(j));
    };
    int checked = 0, bad = 0, grazing = 0;
    double worst = 0.0;
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        const glm::vec3 got = out.views[0].linear[std::size_t(y) * kSize + std::size_t(x)];
        ASSERT_TRUE(finite(got)) << "roughness " << roughness;
        ASSERT_GE(std::min({got.x, got.y, got.z}), 0.0f) << "roughness " << roughness;
        glm::vec3 n;
        float nov = 0.0f;
        if (!sphere_hit(view, x, y, n, nov)) continue;
        if (nov < 0.2f) {
          ++grazing;
          continue;
        }
        const glm::vec2 ab = split_sum(nov);
        const glm::vec3 want = (base * ab.x + ab.y) * radiance;
        const double err = glm::length(got - want) / glm::length(want);
        worst = std::max(worst, err);
        ++checked;
        if (err > 0.02) ++bad;
      }
    std::printf("[extreme] metal sphere roughness %g: %d pixels checked (worst %.4f), %d grazing\n",
                double(roughness), checked, worst, grazing);
    EXPECT_GT(checked, 500);
    EXPECT_GT(grazing, 20);
    EXPECT_EQ(bad, 0) << "roughness " << roughness << ", worst " << worst;
  }
}

// Every probe inactive (all inside geometry): the validity-weighted interpolation has a zero
// weight sum everywhere; the renderer gives zero indirect light, exactly, with no NaN from
// 0 / 0, so a sphere lit by nothing else renders black.
TEST_F(ExtremeRasterTest, EveryProbeInactiveGivesZeroIndirectAndNoNaN) {
  scene::Scene s = one_mesh_scene(uv_sphere(1.0f, 32, 16), make_material(glm::vec3(0.8f), 1.0f, 0.2f));
  sh::ShRgb bright(2);
  bright[0] = glm::vec3(10.0f);
  probes::ProbeVolume volume = uniform_volume(s, bright);
  for (std::uint32_t i = 0; i < volume.probe_count(); ++i) volume.deactivate(i, true);
  RendererOptions options;
  options.msaa = 1;
  Renderer renderer(device(), s, volume, options);
  const scene::View view = front_view();
  const FrameOutput out = renderer.render(s, std::span(&view, 1));
  int sphere_pixels = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const glm::vec3 got = out.views[0].linear[std::size_t(y) * kSize + std::size_t(x)];
      ASSERT_TRUE(finite(got));
      glm::vec3 n;
      float nov = 0.0f;
      if (!sphere_hit(view, x, y, n, nov)) continue;
      ++sphere_pixels;
      EXPECT_EQ(got, glm::vec3(0.0f)) << x << "," << y;
    }
  EXPECT_GT(sphere_pixels, 300);
}

// Zero-area triangles (repeated vertices, collinear points, zero normals) in front of the
// sphere cover no pixel: the image is bit-identical to the one without them, and finite.
TEST_F(ExtremeRasterTest, ZeroAreaTrianglesChangeNothing) {
  const scene::Material grey = make_material(glm::vec3(0.6f), 0.0f, 0.5f);
  sh::ShRgb constant(2);
  constant[0] = glm::vec3(std::sqrt(4.0f * kTestPi));
  auto render = [&](bool with_degenerate) {
    scene::Scene s = one_mesh_scene(uv_sphere(1.0f, 32, 16), grey);
    if (with_degenerate) {
      scene::Mesh m;
      m.name = "degenerate";
      m.positions = {{0, 0, 1.5f}, {0, 0, 1.5f}, {0.5f, 0.2f, 1.5f},
                     {-0.5f, 0, 1.2f}, {0, 0, 1.2f}, {0.5f, 0, 1.2f}};
      m.normals.assign(6, glm::vec3(0.0f));
      m.uvs.assign(6, glm::vec2(0.0f));
      m.tangents.assign(6, glm::vec4(0.0f));
      m.indices = {0, 1, 2, 3, 4, 5};
      for (const glm::vec3& p : m.positions) m.bounds.expand(p);
      add_instance(s, m, grey, glm::vec3(0.0f));
    }
    const probes::ProbeVolume volume = uniform_volume(s, constant);
    RendererOptions options;
    options.msaa = 1;
    Renderer renderer(device(), s, volume, options);
    const scene::View view = front_view();
    return renderer.render(s, std::span(&view, 1)).views[0].linear.to_floats();
  };
  const std::vector<glm::vec3> plain = render(false), degenerate = render(true);
  ASSERT_EQ(plain.size(), degenerate.size());
  int differing = 0;
  for (std::size_t i = 0; i < plain.size(); ++i) {
    ASSERT_TRUE(finite(degenerate[i]));
    if (plain[i] != degenerate[i]) ++differing;
  }
  EXPECT_EQ(differing, 0);
}

// A 64 x 64 x 64 L2 volume (262,144 probes) on the GPU: 7 RGBA16F 3D textures of 64^3 texels,
// 56 B a probe, 14,680,064 bytes staged and copied in one full upload; the corner probes read
// back their own L0 through the shader.
TEST_F(ExtremeRasterTest, SixtyFourCubedVolumeUploads) {
  probes::ProbeVolume volume(probes::ProbeGrid(scene::Aabb{glm::vec3(0.0f), glm::vec3(64.0f)}, {64, 64, 64}), 2);
  const std::uint32_t last = volume.probe_count() - 1;
  for (std::uint32_t i : {0u, 4095u, last}) {
    sh::ShRgb s(2);
    s[0] = glm::vec3(1.0f + float(i % 7), 2.0f, 0.25f);
    volume.set_sh(i, s);
  }
  ProbeTextures textures(device(), volume);
  EXPECT_EQ(textures.texture_count(), 7u);
  const ProbeUploadStats stats = textures.upload(runner(), volume);
  std::printf("[extreme] 64^3 L2 upload: %u probes, %llu bytes\n", stats.probes,
              static_cast<unsigned long long>(stats.bytes));
  EXPECT_TRUE(stats.full);
  EXPECT_EQ(stats.probes, 262144u);
  EXPECT_EQ(stats.bytes, 262144ull * 56ull);
  EXPECT_EQ(stats.clamps.overflowed + stats.clamps.not_finite, 0u);
  std::vector<Query> queries;
  for (std::uint32_t i : {0u, 4095u, last, 1u}) queries.push_back(l0_query(volume.grid().position(i)));
  const auto results = Harness(device(), textures, brdf(), 2).run(runner(), queries);
  for (std::size_t q = 0; q < 3; ++q) {
    const std::uint32_t i = q == 0 ? 0u : q == 1 ? 4095u : last;
    EXPECT_NEAR(results[q].x, 1.0f + float(i % 7), 1e-3f) << i;
    EXPECT_NEAR(results[q].y, 2.0f, 1e-3f) << i;
  }
  EXPECT_EQ(glm::vec3(results[3]), glm::vec3(0.0f));  // an untouched probe
}

// Shadow maps and depth at 1e-3, 1 and 1e4 metre scale: direct_light_test's sunlit glossy
// ground with a sphere casting a shadow, every length (geometry, camera, light placement, near
// and far planes: 0.01 and 1000 times the scale, a 1e5 ratio) multiplied by the scale. Lit
// pixels (the shadow ray clears the sphere by 35 % of its radius) must match the BSDF within
// 3 %, and the fraction of them darkened (acne) must stay at 0 of ~4900; shadowed pixels (the
// ray passes within 70 % of the radius of the centre) must stay dark (< 5 % of the lit value).
class ExtremeShadowScale : public gpu::test::GpuTest, public ::testing::WithParamInterface<float> {};

TEST_P(ExtremeShadowScale, SunShadowIsWhereItShouldBeWithoutAcne) {
  const float k = GetParam();
  const float half = 2.0f * k, radius = 0.3f * k;
  const glm::vec3 centre = glm::vec3(0.0f, 0.8f, 0.0f) * k;
  const scene::Material ground_material = make_material({0.7f, 0.6f, 0.5f}, 0.3f, 0.45f);
  scene::Scene s = one_mesh_scene(ground_quad(half), ground_material);
  add_instance(s, uv_sphere(radius, 48, 24), make_material({0.8f, 0.8f, 0.8f}, 0.0f, 0.8f), centre);
  scene::Light sun;
  sun.name = "sun";
  sun.type = scene::LightType::Directional;
  sun.intensity = 3.0f;
  add_light(s, sun, glm::vec3(0.0f, 5.0f, 0.0f) * k, {-0.3f, -1.0f, -0.2f});
  const scene::Light& light = s.lights.front();
  const probes::ProbeVolume volume(probes::ProbeGrid(s.bounds(), {2, 2, 2}));
  RendererOptions options;
  options.msaa = 1;
  options.probes = false;
  Renderer renderer(device(), s, volume, options);
  const int size = 96;
  const scene::View view = scene::look_at_view(glm::vec3(0.0f, 3.5f, 3.5f) * k, glm::vec3(0.0f),
                                               {0.0f, 1.0f, 0.0f}, glm::radians(50.0f), size, size,
                                               0.01f * k, 1000.0f * k);
  const FrameOutput out = renderer.render(s, std::span(&view, 1));
  const trace::Bsdf bsdf({glm::vec3(ground_material.base_color), ground_material.metallic,
                          ground_material.roughness});
  auto clearance = [&](const glm::vec3& p, const glm::vec3& d, float dist) {
    const float t = std::clamp(glm::dot(centre - p, d), 0.0f, dist);
    return glm::length(p + d * t - centre);
  };
  ShadowTally tally;  // lit_bad counts acne, shadow_bad counts leaks
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const scene::Ray ray = scene::view_ray(view, float(x) + 0.5f, float(y) + 0.5f);
      if (ray.direction.y >= 0.0f) continue;
      const glm::vec3 p = ray.origin + ray.direction * (-ray.origin.y / ray.direction.y);
      if (std::abs(p.x) > half - 0.05f * k || std::abs(p.z) > half - 0.05f * k) continue;
      if (clearance(ray.origin, ray.direction, glm::length(p - ray.origin)) < radius * 1.1f) continue;
      trace::LightSample ls;
      if (!trace::sample_punctual(light, p, ls)) continue;
      auto local = [](const glm::vec3& w) { return glm::vec3(w.x, -w.z, w.y); };
      const glm::vec3 expected = bsdf.eval(local(-ray.direction), local(ls.wi)) * ls.wi.y * ls.radiance;
      const glm::vec3 got = out.views[0].linear[std::size_t(y) * size + std::size_t(x)];
      ASSERT_TRUE(finite(got));
      tally.add(got, expected, clearance(p, ls.wi, 100.0f * k), radius);
    }
  std::printf("[extreme] shadows at scale %g: %d lit (%d wrong, worst %.4f), %d shadowed (%d lit)\n",
              double(k), tally.lit, tally.lit_bad, tally.worst, tally.shadowed, tally.shadow_bad);
  EXPECT_GT(tally.lit, 1500);
  EXPECT_GT(tally.shadowed, 15);
  EXPECT_EQ(tally.lit_bad, 0) << "worst relative error " << tally.worst;
  EXPECT_EQ(tally.shadow_bad, 0);
}

INSTANTIATE_TEST_SUITE_P(Scales, ExtremeShadowScale, ::testing::Values(1e-3f, 1.0f, 1e4f),
                         [](const ::testing::TestParamInfo<float>& i) {
                           return i.param < 0.5f ? std::string("millimetre")
                                  : i.param > 2.0f ? std::string("ten_km")
                                                   : std::string("metre");
                         });

}  // namespace
}  // namespace ddish::raster::test
