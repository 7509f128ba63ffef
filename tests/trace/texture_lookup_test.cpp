// Mip chains, filtering, sRGB decoding, footprint-based level selection, and textures reaching
// the shading point (emissive colour, normal maps) through the whole tracer.
#include <cmath>

#include <gtest/gtest.h>

#include "trace/texture_lookup.h"
#include "trace_test_scenes.h"

namespace ddish::trace {
namespace {

using testing::add_material;
using testing::add_quad;

TEST(MipTexture, BoxFilteredChain) {
  // 4×4 grey ramp: texel value 16·(x + 4y).
  const scene::Texture t = testing::solid_texture(4, 4, [](int x, int y) {
    const auto v = static_cast<std::uint8_t>(16 * (x + 4 * y));
    return glm::u8vec4(v, v, v, 255);
  });
  const MipTexture mip(t);
  ASSERT_EQ(mip.levels(), 3);
  EXPECT_EQ(mip.width(1), 2);
  // Level 1 texel (0,0) averages texels (0,0), (1,0), (0,1), (1,1): 16·(0+1+4+5)/4 = 40.
  EXPECT_NEAR(mip.texel(1, 0, 0, false).r, 40.0f / 255.0f, 1e-6f);
  // Level 2 is the mean of everything: 16·7.5 = 120.
  EXPECT_NEAR(mip.texel(2, 0, 0, false).r, 120.0f / 255.0f, 1e-6f);

  // Odd and non-square sizes halve (rounding down) to 1×1.
  const scene::Texture odd_texture = testing::solid_texture(5, 3, [](int, int) { return glm::u8vec4(9); });
  const MipTexture odd(odd_texture);
  ASSERT_EQ(odd.levels(), 3);
  EXPECT_EQ(odd.width(1), 2);
  EXPECT_EQ(odd.height(1), 1);
  EXPECT_EQ(odd.width(2), 1);
}

TEST(MipTexture, BilinearWrapAndSrgb) {
  const scene::Texture t = testing::solid_texture(
      2, 1, [](int x, int) { return x == 0 ? glm::u8vec4(0, 0, 0, 0) : glm::u8vec4(255, 188, 255, 255); });
  const MipTexture mip(t);
  // Texel centres return the texel.
  EXPECT_NEAR(mip.sample_level({0.75f, 0.5f}, 0, false).r, 1.0f, 1e-6f);
  EXPECT_NEAR(mip.sample_level({0.25f, 0.5f}, 0, false).r, 0.0f, 1e-6f);
  // Halfway between centres: the mean; across the u = 0 seam the wrap blends last and first.
  EXPECT_NEAR(mip.sample_level({0.5f, 0.5f}, 0, false).r, 0.5f, 1e-6f);
  EXPECT_NEAR(mip.sample_level({0.0f, 0.5f}, 0, false).r, 0.5f, 1e-6f);
  EXPECT_NEAR(mip.sample_level({1.0f, 0.5f}, 0, false).r, 0.5f, 1e-6f);
  EXPECT_NEAR(mip.sample_level({-3.75f, 7.5f}, 0, false).r, 0.0f, 1e-6f);
  // sRGB decoding: code 188 is linear 0.5029 (IEC 61966-2-1); alpha stays linear.
  EXPECT_NEAR(mip.sample_level({0.75f, 0.5f}, 0, true).g, 0.50289f, 1e-4f);
  EXPECT_NEAR(srgb_to_linear(255), 1.0f, 1e-7f);
  EXPECT_NEAR(srgb_to_linear(10), 10.0f / 255.0f / 12.92f, 1e-7f);
  // Decoding happens before filtering: the mean of linear 0 and 1, not decode(mean code).
  EXPECT_NEAR(mip.sample_level({0.5f, 0.5f}, 0, true).r, 0.5f, 1e-6f);
  // Trilinear: halfway between level 0 (a texel centre: 1) and level 1 (the mean 0.5).
  EXPECT_NEAR(mip.sample({0.75f, 0.5f}, 0.5f, false).r, 0.75f, 2e-3f);
}

TEST(MipTexture, SamplerWrapModes) {
  const scene::Texture t = testing::solid_texture(
      2, 1, [](int x, int) { return x == 0 ? glm::u8vec4(0, 0, 0, 255) : glm::u8vec4(255, 255, 255, 255); });
  const MipTexture mip(t);
  const MipTexture::Wrap clamp{scene::Wrap::ClampToEdge, scene::Wrap::ClampToEdge};
  const MipTexture::Wrap mirror{scene::Wrap::MirroredRepeat, scene::Wrap::MirroredRepeat};
  // Clamping: the edges keep their own texel, far outside too.
  EXPECT_NEAR(mip.sample_level({0.0f, 0.5f}, 0, false, clamp).r, 0.0f, 1e-6f);
  EXPECT_NEAR(mip.sample_level({1.0f, 0.5f}, 0, false, clamp).r, 1.0f, 1e-6f);
  EXPECT_NEAR(mip.sample_level({-7.0f, 0.5f}, 0, false, clamp).r, 0.0f, 1e-6f);
  EXPECT_NEAR(mip.sample_level({1e9f, 0.5f}, 0, false, clamp).r, 1.0f, 1e-6f);
  // Mirrored repeat: [1, 2] reads [0, 1] backwards, and the seams do not blend opposite edges.
  EXPECT_NEAR(mip.sample_level({1.25f, 0.5f}, 0, false, mirror).r, 1.0f, 1e-6f);
  EXPECT_NEAR(mip.sample_level({1.75f, 0.5f}, 0, false, mirror).r, 0.0f, 1e-6f);
  EXPECT_NEAR(mip.sample_level({-0.25f, 0.5f}, 0, false, mirror).r, 0.0f, 1e-6f);
  EXPECT_NEAR(mip.sample_level({0.0f, 0.5f}, 0, false, mirror).r, 0.0f, 1e-6f);
  EXPECT_NEAR(mip.sample_level({2.0f, 0.5f}, 0, false, mirror).r, 0.0f, 1e-6f);
}

// glTF sampler filters: magnification (lod <= 0) by magFilter, minification by minFilter and its
// mipmap mode. A 4 x 1 ramp 0, 1/3, 2/3, 1 (level 1: 1/6, 5/6; level 2: 1/2).
TEST(MipTexture, SamplerFilterModes) {
  const scene::Texture t = testing::solid_texture(4, 1, [](int x, int) {
    const auto v = static_cast<std::uint8_t>(85 * x);
    return glm::u8vec4(v, v, v, 255);
  });
  const MipTexture mip(t);
  ASSERT_EQ(mip.levels(), 3);
  using scene::Filter;
  using scene::MipFilter;
  auto modes = [](Filter mag, Filter min, MipFilter mip_mode) {
    return MipTexture::Wrap{scene::Wrap::ClampToEdge, scene::Wrap::ClampToEdge, mag, min, mip_mode};
  };
  const float u = 0.3f;  // between texel centres 0.125 and 0.375: 0.7 of the way to texel 1
  // Magnification: nearest is texel 1 (u * 4 = 1.2), linear blends texels 0 and 1.
  EXPECT_NEAR(mip.sample({u, 0.5f}, -1.0f, false, modes(Filter::Nearest, Filter::Linear, MipFilter::Linear)).r,
              85.0f / 255.0f, 1e-6f);
  EXPECT_NEAR(mip.sample({u, 0.5f}, -1.0f, false, modes(Filter::Linear, Filter::Nearest, MipFilter::None)).r,
              0.7f * 85.0f / 255.0f, 1e-5f);
  // Minification at lod 0.75: no mipmaps reads level 0 (with the min filter), nearest mipmap
  // reads level 1 (floor(0.75 + 0.5)), linear blends levels 0 and 1 by 0.75.
  const float level0_nearest = 85.0f / 255.0f;
  EXPECT_NEAR(mip.sample({u, 0.5f}, 0.75f, false, modes(Filter::Linear, Filter::Nearest, MipFilter::None)).r,
              level0_nearest, 1e-6f);
  const float level1_texel0 = mip.texel(1, 0, 0, false).r;  // (0 + 85 + 1) / 2 rounded: 43
  EXPECT_NEAR(mip.sample({u, 0.5f}, 0.75f, false, modes(Filter::Linear, Filter::Nearest, MipFilter::Nearest)).r,
              level1_texel0, 1e-6f);
  const float level1_linear =
      mip.sample_level({u, 0.5f}, 1, false, modes(Filter::Linear, Filter::Linear, MipFilter::Linear)).r;
  const float level0_linear = mip.sample_level({u, 0.5f}, 0, false, modes(Filter::Linear, Filter::Linear, MipFilter::Linear)).r;
  EXPECT_NEAR(mip.sample({u, 0.5f}, 0.75f, false, modes(Filter::Linear, Filter::Linear, MipFilter::Linear)).r,
              level0_linear + 0.75f * (level1_linear - level0_linear), 1e-6f);
  // At lod 0.25 nearest mipmap stays on level 0.
  EXPECT_NEAR(mip.sample({u, 0.5f}, 0.25f, false, modes(Filter::Linear, Filter::Nearest, MipFilter::Nearest)).r,
              level0_nearest, 1e-6f);
}

TEST(MipTexture, LevelFromFootprint) {
  const scene::Texture t = testing::solid_texture(256, 256, [](int, int) { return glm::u8vec4(1); });
  const MipTexture mip(t);
  // A 1 m² quad mapped once: 256 texels per metre.
  EXPECT_NEAR(mip.lod_for_footprint(1.0f / 256.0f, 1.0f, 1.0f, 1.0f), 0.0f, 1e-5f);
  EXPECT_NEAR(mip.lod_for_footprint(4.0f / 256.0f, 1.0f, 1.0f, 1.0f), 2.0f, 1e-5f);
  // Seen at 60° the footprint doubles: one level more.
  EXPECT_NEAR(mip.lod_for_footprint(4.0f / 256.0f, 0.5f, 1.0f, 1.0f), 3.0f, 1e-5f);
  // UV tiled 4× in each direction: 4× the texels per metre, two levels more.
  EXPECT_NEAR(mip.lod_for_footprint(4.0f / 256.0f, 1.0f, 16.0f, 1.0f), 4.0f, 1e-5f);
  EXPECT_EQ(mip.lod_for_footprint(0.0f, 1.0f, 1.0f, 1.0f), 0.0f);
}

TEST(SurfaceTextures, EmissiveTextureThroughTracer) {
  scene::Scene s;
  s.textures.push_back(testing::solid_texture(4, 4, [](int, int) { return glm::u8vec4(188, 255, 0, 255); }));
  scene::Material m = testing::emitter(glm::vec3(2.0f));
  m.emissive_texture.texture = 0;
  add_quad(s, {0, 0, -2}, {1, 0, 0}, {0, 1, 0}, add_material(s, m));
  PathOptions opt;
  opt.max_bounces = 0;
  Tracer tracer(s, opt);
  Sampler sampler(1, 0);
  // With a wide ray cone (coarsest level) and without one (finest): a uniform texture reads the same.
  for (float spread : {0.0f, 0.5f}) {
    Ray ray{{0.3f, -0.2f, 0}, {0, 0, -1}};
    ray.cone_spread = spread;
    const glm::vec3 l = tracer.trace_path(ray, sampler).radiance;
    EXPECT_NEAR(l.r, 2.0f * srgb_to_linear(188), 1e-5f);
    EXPECT_NEAR(l.g, 2.0f, 1e-5f);
    EXPECT_EQ(l.b, 0.0f);
  }
}

TEST(SurfaceTextures, NormalMapTiltsShading) {
  // A floor facing +y with tangent +x (bitangent cross(n, t) = -z). The normal map tilts the
  // shading normal by 30° toward +x; a directional light from exactly that direction then
  // arrives at normal incidence to the shading frame.
  const float tilt = 0.5235988f;
  const glm::u8vec4 code(static_cast<std::uint8_t>(std::lround(127.5f + 127.5f * std::sin(tilt))), 128,
                         static_cast<std::uint8_t>(std::lround(127.5f + 127.5f * std::cos(tilt))), 255);
  scene::Scene s;
  s.textures.push_back(testing::solid_texture(2, 2, [&](int, int) { return code; }));
  scene::Material m = testing::diffuse(glm::vec3(0.5f), 0.6f);
  m.normal_texture.texture = 0;
  add_quad(s, {0, 0, 0}, {10, 0, 0}, {0, 0, -10}, add_material(s, m));  // cross(x, -z) = +y
  // The decoded tangent-space normal, as the tracer will see it.
  const glm::vec3 ts = glm::normalize(glm::vec3(code.r, code.g, code.b) / 255.0f * 2.0f - 1.0f);
  const glm::vec3 n_world =
      glm::normalize(ts.x * glm::vec3(1, 0, 0) + ts.y * glm::vec3(0, 0, -1) + ts.z * glm::vec3(0, 1, 0));
  scene::Light sun;
  sun.type = scene::LightType::Directional;
  sun.intensity = 2.0f;
  sun.direction = -n_world;
  s.lights.push_back(sun);
  PathOptions opt;
  opt.max_bounces = 1;
  opt.fixed_mip_level = 0;
  Tracer tracer(s, opt);
  Sampler sampler(1, 0);
  const glm::vec3 l = tracer.trace_path(Ray{{0, 1, 0}, {0, -1, 0}}, sampler).radiance;
  // Expected: E · f(wo, n') with wo = +y expressed in the shading frame, wi = n'.
  const glm::vec3 t = glm::normalize(glm::vec3(1, 0, 0) - n_world * n_world.x);
  const glm::vec3 b = glm::cross(n_world, t);
  const glm::vec3 wo(glm::dot(glm::vec3(0, 1, 0), t), glm::dot(glm::vec3(0, 1, 0), b),
                     glm::dot(glm::vec3(0, 1, 0), n_world));
  const float expected = 2.0f * Bsdf({glm::vec3(0.5f), 0.0f, 0.6f}).eval(wo, {0, 0, 1}).x;
  EXPECT_NEAR(l.x, expected, 1e-4f * expected);
  // Without the map the light would arrive at 30° off the normal: visibly less.
  EXPECT_LT(2.0f *
                Bsdf({glm::vec3(0.5f), 0.0f, 0.6f}).eval({0, 0, 1}, {std::sin(tilt), 0, std::cos(tilt)}).x *
                std::cos(tilt),
            0.95f * l.x);
}

}  // namespace
}  // namespace ddish::trace
