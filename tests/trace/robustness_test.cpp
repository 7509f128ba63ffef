// Determinism, degenerate input, alpha testing, instance updates and self-intersection at
// millimetre and ten-kilometre scales.
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include "trace/embree_scene.h"
#include "trace/sampling.h"
#include "trace/surface.h"
#include "trace/texture_lookup.h"
#include "trace_test_scenes.h"

namespace ddish::trace {
namespace {

using testing::add_material;
using testing::add_quad;

// A small Cornell-like room: white box, a red and a green wall, a ceiling emitter, a point light.
scene::Scene room() {
  scene::Scene s;
  testing::add_box_inward(s, {-1, 0, -1}, {1, 2, 1},
                          add_material(s, testing::diffuse(glm::vec3(0.7f), 0.8f)));
  add_quad(s, {-0.99f, 1, 0}, {0, 1, 0}, {0, 0, 1}, add_material(s, testing::diffuse({0.7f, 0.1f, 0.1f})));
  add_quad(s, {0, 1.99f, 0}, {0.3f, 0, 0}, {0, 0, 0.3f}, add_material(s, testing::emitter(glm::vec3(10.0f))));
  scene::Light l;
  l.position = {0.5f, 1.5f, 0.5f};
  l.intensity = 2.0f;
  s.lights.push_back(l);
  return s;
}

TEST(Tracer, SameSeedSameBits) {
  const scene::Scene s = room();
  Tracer a(s);
  Tracer b(s);
  for (int i = 0; i < 200; ++i) {
    const Ray ray{{0, 1, 0.9f}, sample_uniform_sphere({float(i) / 200.0f, 0.37f})};
    Sampler sa(42, 5, static_cast<std::uint64_t>(i));
    Sampler sb(42, 5, static_cast<std::uint64_t>(i));
    const glm::vec3 ra = a.trace_path(ray, sa).radiance;
    const glm::vec3 rb = b.trace_path(ray, sb).radiance;
    ASSERT_EQ(std::memcmp(&ra, &rb, sizeof ra), 0) << i;
  }
  EXPECT_EQ(a.rays_traced(), b.rays_traced());
  // A different seed gives a different estimate.
  const Ray ray{{0, 1, 0.9f}, {0, -1, 0}};
  Sampler s1(1, 0), s2(2, 0);
  EXPECT_NE(a.trace_path(ray, s1).radiance, a.trace_path(ray, s2).radiance);
}

TEST(Tracer, ConcurrentPathsMatchSequentialOnes) {
  const scene::Scene s = room();
  Tracer sequential(s);
  Tracer concurrent(s);
  const int n = 4000;
  std::vector<glm::vec3> expected(n), got(n);
  auto ray = [](int i) {
    return Ray{{0, 1, 0},
               sample_uniform_sphere({(float(i) + 0.5f) / float(n), std::fmod(0.754877f * float(i), 1.0f)})};
  };
  for (int i = 0; i < n; ++i) {
    Sampler sampler(3, static_cast<std::uint64_t>(i));
    expected[static_cast<std::size_t>(i)] = sequential.trace_path(ray(i), sampler).radiance;
  }
  tbb::parallel_for(0, n, [&](int i) {
    Sampler sampler(3, static_cast<std::uint64_t>(i));
    got[static_cast<std::size_t>(i)] = concurrent.trace_path(ray(i), sampler).radiance;
  });
  EXPECT_EQ(std::memcmp(expected.data(), got.data(), sizeof(glm::vec3) * n), 0);
  EXPECT_EQ(sequential.rays_traced(), concurrent.rays_traced());
  EXPECT_GT(concurrent.rays_traced(), 2u * n);
}

TEST(Tracer, NonFiniteRadianceIsCaughtAndCounted) {
  scene::Scene s;
  add_quad(s, {0, 0, -2}, {1, 0, 0}, {0, 1, 0},
           add_material(s, testing::emitter(glm::vec3(std::numeric_limits<float>::infinity(), 1, 1))));
  Tracer tracer(s);
  Sampler sampler(1, 0);
  EXPECT_EQ(tracer.trace_path(Ray{{0.1f, 0.2f, 0}, {0, 0, -1}}, sampler).radiance, glm::vec3(0.0f));
  EXPECT_EQ(tracer.invalid_paths(), 1u);
}

TEST(Tracer, DegenerateTrianglesGiveFiniteRadiance) {
  scene::Scene s = room();
  // Zero-area triangles (a repeated vertex, collinear points) with zero normals, emissive too.
  const int emissive = add_material(s, testing::emitter(glm::vec3(5.0f)));
  const int mesh = testing::add_mesh(
      s, {{0, 1, 0}, {0, 1, 0}, {0.5f, 1, 0}, {0.2f, 0.5f, 0}, {0.4f, 0.5f, 0}, {0.6f, 0.5f, 0}},
      {0, 1, 2, 3, 4, 5}, emissive, {}, std::vector<glm::vec3>(6, glm::vec3(0.0f)));
  testing::add_instance(s, mesh);
  // And a triangle squeezed to a sliver right in front of the camera.
  testing::add_instance(
      s, testing::add_mesh(s, {{-0.1f, 1, 0.5f}, {0.1f, 1, 0.5f}, {0.0f, 1.0f + 1e-30f, 0.5f}}, {0, 1, 2},
                           emissive));
  PathOptions opt;
  opt.max_bounces = 6;
  opt.rr_min_bounces = 1;
  Tracer tracer(s, opt);
  for (int i = 0; i < 2000; ++i) {
    Sampler sampler(9, 0, static_cast<std::uint64_t>(i));
    const Ray ray{
        {0, 1, 0.9f},
        sample_uniform_sphere({(i + 0.5f) / 2000.0f, 0.61803f * float(i) - std::floor(0.61803f * float(i))})};
    const glm::vec3 l = tracer.trace_path(ray, sampler).radiance;
    ASSERT_TRUE(std::isfinite(l.x) && std::isfinite(l.y) && std::isfinite(l.z)) << i;
  }
  EXPECT_EQ(tracer.invalid_paths(), 0u);
}

scene::Scene masked_quad_over_emitter(scene::AlphaMode mode, float alpha, int texture = -1) {
  scene::Scene s;
  add_quad(s, {0, 0, -4}, {2, 0, 0}, {0, 2, 0}, add_material(s, testing::emitter(glm::vec3(1.0f))));
  scene::Material leaf = testing::diffuse(glm::vec3(0.0f));
  leaf.base_color.a = alpha;
  leaf.alpha_mode = mode;
  leaf.alpha_cutoff = 0.5f;
  leaf.base_color_texture.texture = texture;
  add_quad(s, {0, 0, -2}, {1, 0, 0}, {0, 1, 0}, add_material(s, leaf));
  return s;
}

TEST(AlphaMask, FactorBelowCutoffIsInvisible) {
  PathOptions opt;
  opt.max_bounces = 0;
  for (float alpha : {0.3f, 0.7f}) {
    const scene::Scene s = masked_quad_over_emitter(scene::AlphaMode::Mask, alpha);
    Tracer tracer(s, opt);
    Sampler sampler(1, 0);
    const PathSample p = tracer.trace_path(Ray{{0, 0, 0}, {0, 0, -1}}, sampler);
    EXPECT_NEAR(p.hit_distance, alpha < 0.5f ? 4.0f : 2.0f, 1e-5f);
    EXPECT_EQ(p.radiance.x, alpha < 0.5f ? 1.0f : 0.0f);
  }
}

TEST(AlphaMask, TextureAlphaRejectsHitsAndShadows) {
  // Left half of the texture (u < 0.5) transparent, right half opaque.
  scene::Scene s = masked_quad_over_emitter(scene::AlphaMode::Mask, 1.0f, 0);
  s.textures.push_back(
      testing::solid_texture(8, 8, [](int x, int) { return glm::u8vec4(255, 255, 255, x < 4 ? 0 : 255); }));
  PathOptions opt;
  opt.max_bounces = 0;
  opt.fixed_mip_level = 0;
  Tracer tracer(s, opt);
  Sampler sampler(1, 0);
  EXPECT_NEAR(tracer.trace_path(Ray{{-0.5f, 0, 0}, {0, 0, -1}}, sampler).hit_distance, 4.0f, 1e-5f);
  EXPECT_NEAR(tracer.trace_path(Ray{{0.5f, 0, 0}, {0, 0, -1}}, sampler).hit_distance, 2.0f, 1e-5f);

  // Shadow rays go through the transparent half only: a floor lit by a point light above the
  // masked quad (now horizontal).
  scene::Scene f;
  add_quad(f, {0, 0, 0}, {0, 0, 10}, {10, 0, 0}, add_material(f, testing::diffuse(glm::vec3(0.5f))));
  scene::Material leaf = testing::diffuse(glm::vec3(0.5f));
  leaf.alpha_mode = scene::AlphaMode::Mask;
  leaf.base_color_texture.texture = 0;
  f.textures = s.textures;
  add_quad(f, {0, 1, 0}, {0, 0, 1}, {1, 0, 0}, add_material(f, leaf));  // faces +y
  scene::Light light;
  light.position = {0, 3, 0};
  f.lights.push_back(light);
  opt.max_bounces = 1;
  Tracer lit(f, opt);
  // The quad's u coordinate runs along its `a` axis (+z): z < 0 is the transparent half.
  Sampler s2(1, 0);
  EXPECT_GT(lit.trace_path(Ray{{0.1f, 0.5f, -0.3f}, {0, -1, 0}}, s2).radiance.x, 0.0f);
  EXPECT_EQ(lit.trace_path(Ray{{0.1f, 0.5f, 0.3f}, {0, -1, 0}}, s2).radiance.x, 0.0f);
}

TEST(AlphaBlend, StochasticTransparencyAveragesToAlpha) {
  const float alpha = 0.25f;
  const scene::Scene s = masked_quad_over_emitter(scene::AlphaMode::Blend, alpha);
  PathOptions opt;
  opt.max_bounces = 0;
  Tracer tracer(s, opt);
  const int n = 20000;
  // Off the quad's diagonal: a ray exactly through the edge two triangles share meets both, and
  // each decides independently (a measure-zero set of rays).
  const testing::Estimate e = testing::estimate(tracer, Ray{{0.31f, -0.17f, 0}, {0, 0, -1}}, n);
  // A black quad of coverage alpha in front of radiance 1: 1 - alpha gets through.
  testing::report("stochastic alpha blend", e.mean.x, e.stderr_.x, 1.0 - alpha);
  EXPECT_NEAR(e.mean.x, 1.0 - alpha, 4.0 * e.stderr_.x);
}

TEST(Tracer, UpdateMovesInstance) {
  scene::Scene s;
  const int q =
      add_quad(s, {0, 0, -3}, {1, 0, 0}, {0, 1, 0}, add_material(s, testing::emitter(glm::vec3(1, 2, 3))));
  add_quad(s, {0, 0, -8}, {5, 0, 0}, {0, 5, 0}, add_material(s, testing::emitter(glm::vec3(7))));
  Tracer tracer(s);
  Sampler sampler(1, 0);
  const Ray ray{{0, 0, 0}, {0, 0, -1}};
  EXPECT_NEAR(tracer.trace_path(ray, sampler).hit_distance, 3.0f, 1e-5f);
  // Move the small quad 4 m to the side: the ray now reaches the back wall.
  s.instances[static_cast<std::size_t>(q)].transform = glm::mat4(1.0f);
  s.instances[static_cast<std::size_t>(q)].transform[3] = glm::vec4(4, 0, 1, 1);
  const int moved[] = {q};
  tracer.update(s, moved);
  const PathSample p = tracer.trace_path(ray, sampler);
  EXPECT_NEAR(p.hit_distance, 8.0f, 1e-5f);
  EXPECT_EQ(p.radiance, glm::vec3(7));
  // ... and it is hit where it went (at z = -2 now), with its emission.
  const PathSample side = tracer.trace_path(Ray{{4, 0, 0}, {0, 0, -1}}, sampler);
  EXPECT_NEAR(side.hit_distance, 2.0f, 1e-5f);
  EXPECT_EQ(side.radiance, glm::vec3(1, 2, 3));
}

TEST(Tracer, MirroredInstanceKeepsItsFrontFace) {
  // glTF: under a transform with negative determinant, clockwise triangles face the front. A
  // mirrored emitter must still face the way its normals say, for hits and for light sampling.
  auto make = [](bool mirror) {
    scene::Scene s;
    add_quad(s, {0, 0, 0}, {0, 0, 10}, {10, 0, 0}, add_material(s, testing::diffuse(glm::vec3(0.5f))));
    const int light =
        add_quad(s, {0, 1, 0}, {0.5f, 0, 0}, {0, 0, 0.5f}, add_material(s, testing::emitter(glm::vec3(4))));
    if (mirror)
      s.instances[static_cast<std::size_t>(light)].transform = glm::mat4(
          glm::vec4(-1, 0, 0, 0), glm::vec4(0, 1, 0, 0), glm::vec4(0, 0, 1, 0), glm::vec4(0, 0, 0, 1));
    return s;
  };
  PathOptions opt;
  opt.max_bounces = 1;
  const scene::Scene plain = make(false);
  const scene::Scene mirrored = make(true);
  Tracer a(plain, opt);
  Tracer b(mirrored, opt);
  Sampler sampler(1, 0);
  const PathSample seen = b.trace_path(Ray{{0.1f, 0.5f, 0.1f}, {0, 1, 0}}, sampler);
  EXPECT_FALSE(seen.backface);
  EXPECT_EQ(seen.radiance, glm::vec3(4));
  const Ray down{{0.2f, 0.5f, 0.1f}, {0, -1, 0}};
  const testing::Estimate ea = testing::estimate(a, down, 4000);
  const testing::Estimate eb = testing::estimate(b, down, 4000);
  EXPECT_GT(ea.mean.x, 0.1);
  EXPECT_NEAR(ea.mean.x, eb.mean.x, 4.0 * std::hypot(ea.stderr_.x, eb.stderr_.x));
}

TEST(Tracer, UpdateMovesEmissiveLights) {
  // A floor lit by a small emitter; after the emitter moves 50 m away, next-event estimation
  // must sample it where it is now (a stale light list would keep lighting the floor).
  scene::Scene s;
  add_quad(s, {0, 0, 0}, {0, 0, 100}, {100, 0, 0}, add_material(s, testing::diffuse(glm::vec3(0.5f))));
  const int light =
      add_quad(s, {0, 1, 0}, {0.2f, 0, 0}, {0, 0, 0.2f}, add_material(s, testing::emitter(glm::vec3(10))));
  PathOptions opt;
  opt.max_bounces = 1;
  Tracer tracer(s, opt);
  const Ray down{{0, 0.5f, 0}, {0, -1, 0}};
  const testing::Estimate before = testing::estimate(tracer, down, 2000);
  s.instances[static_cast<std::size_t>(light)].transform[3] = glm::vec4(50, 0, 0, 1);
  const int moved[] = {light};
  tracer.update(s, moved);
  const testing::Estimate after = testing::estimate(tracer, down, 2000);
  // Irradiance from a 0.16 m² emitter of radiance 10 at 1 m straight above vs ~50 m to the side.
  EXPECT_GT(before.mean.x, 0.1);
  EXPECT_LT(after.mean.x, 1e-4 * before.mean.x);
}

// Rays leaving a tilted plane far from the origin, in every direction of the side they leave
// from, must never hit the plane they start on.
class RayOffset : public ::testing::TestWithParam<float> {};

TEST_P(RayOffset, NoSelfIntersection) {
  const float scale = GetParam();
  scene::Scene s;
  const glm::vec3 centre = scale * glm::vec3(3.1f, -2.7f, 5.3f);
  const glm::vec3 a = scale * glm::normalize(glm::vec3(1.0f, 0.3f, -0.2f));
  const glm::vec3 b = scale * glm::normalize(glm::cross(glm::vec3(0.2f, 1.0f, 0.4f), a));
  scene::Material m = testing::diffuse(glm::vec3(0.5f));
  m.double_sided = true;
  add_quad(s, centre, a, b, add_material(s, m));
  const TextureSet textures(s);
  const EmbreeScene embree(s, textures);
  const glm::vec3 n = glm::normalize(glm::cross(a, b));
  int self_hits = 0;
  int trials = 0;
  for (int i = 0; i < 64; ++i) {
    // Aim at a point on the plane from above it.
    const glm::vec3 target = centre + a * (float(i % 8) / 8.0f - 0.45f) + b * (float(i / 8) / 8.0f - 0.43f);
    const glm::vec3 eye = target + scale * (n + 0.3f * glm::normalize(a));
    Ray ray{eye, glm::normalize(target - eye)};
    Hit hit;
    ASSERT_TRUE(embree.intersect(ray, RayQuery{}, hit));
    HitInput in;
    in.mesh = &s.meshes[0];
    in.material = &s.materials[0];
    in.transform = &embree.transform(hit.instance);
    in.triangle = &embree.triangle(0, hit.prim);
    in.prim = hit.prim;
    in.u = hit.u;
    in.v = hit.v;
    in.direction = ray.direction;
    const SurfacePoint sp = make_surface_point(in, textures);
    for (float side : {1.0f, -1.0f}) {
      const glm::vec3 o = offset_ray_origin(sp.position, side * sp.ng, sp.offset_scale);
      for (int k = 0; k < 64; ++k) {
        // Directions of the leaving side down to 0.06° above the plane.
        const float cos_theta =
            k < 32 ? std::pow(10.0f, -3.0f + 3.0f * float(k) / 32.0f) : float(k - 31) / 33.0f;
        const float phi = 2.399963f * float(k + i);
        const float sin_theta = std::sqrt(1.0f - cos_theta * cos_theta);
        const glm::vec3 t = glm::normalize(a);
        const glm::vec3 bt = glm::cross(n, t);
        const glm::vec3 d =
            glm::normalize(side * cos_theta * sp.ng + sin_theta * (std::cos(phi) * t + std::sin(phi) * bt));
        Hit h2;
        ++trials;
        if (embree.intersect(Ray{o, d}, RayQuery{}, h2)) ++self_hits;
        if (embree.occluded(o, d, 0.0f, std::numeric_limits<float>::infinity(), RayQuery{})) ++self_hits;
      }
    }
  }
  EXPECT_EQ(self_hits, 0) << "of " << trials;
}

INSTANTIATE_TEST_SUITE_P(Scales, RayOffset, ::testing::Values(1e-3f, 1.0f, 1e4f));

}  // namespace
}  // namespace ddish::trace
