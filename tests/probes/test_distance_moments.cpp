// Per-probe distance moments (probes/moment_map.h): the octahedral texel mapping, and the means
// a probe update gathers from its rays' first hits against analytic means, for a probe above a
// plane and a probe at the centre of a box.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "probes/moment_map.h"
#include "probes/probe_tracer.h"
#include "synthetic_sources.h"

using namespace ddish::probes;
using ddish::probes::synthetic::FunctionSource;
using ddish::scene::Aabb;
using ddish::trace::PathSample;
using ddish::trace::Ray;
using ddish::trace::Sampler;

namespace {

// One probe at the origin; the moment range is 1.5 diagonals of the bounds [-1, 1]^3.
ProbeVolume one_probe(int resolution) {
  return ProbeVolume(ProbeGrid(Aabb{{-1.0f, -1.0f, -1.0f}, {1.0f, 1.0f, 1.0f}}, {1, 1, 1}), 2,
                     resolution);
}

// The sphere averages of d / range and (d / range)^2 over all texels of one update.
glm::dvec2 sphere_mean(const MomentEstimate& e) {
  glm::dvec2 sum(0.0);
  double n = 0.0;
  for (std::size_t t = 0; t < e.sum.size(); ++t) {
    sum += glm::dvec2(e.sum[t]);
    n += e.count[t];
  }
  return sum / n;
}

}  // namespace

TEST(DistanceMoments, OctahedralTexelsCoverTheSphereAndFoldTheLowerHemisphere) {
  EXPECT_EQ(moment_texel({0.0f, 0.0f, 1.0f}, 4), 2u + 4u * 2u);  // +z: the square's centre
  // -z: a corner of the square (the fold sends it to (+-1, +-1)).
  const std::uint32_t down = moment_texel({0.0f, 0.0f, -1.0f}, 4);
  EXPECT_TRUE(down == 15u);
  EXPECT_EQ(moment_texel({1.0f, 0.0f, 0.0f}, 4), 3u + 4u * 2u);
  EXPECT_EQ(moment_texel({-1.0f, 0.0f, 0.0f}, 4), 0u + 4u * 2u);
  // Every texel receives some of 4096 lattice directions.
  MomentEstimate e(4);
  ProbeVolume v = one_probe(4);
  FunctionSource miss([](const Ray&, Sampler&) { return PathSample{}; });
  UpdateOptions o;
  o.samples = 4096;
  ProbeTracer tracer(miss, o);
  ddish::sh::ShRgb sh(2);
  tracer.trace_probe(v, 0, 1, sh, nullptr, &e);
  for (std::uint32_t c : e.count) EXPECT_GT(c, 4096u / 16u / 3u);
  EXPECT_THROW(check_moment_resolution(kMaxMomentResolution + 1), std::invalid_argument);
  EXPECT_THROW(check_moment_resolution(-1), std::invalid_argument);
}

TEST(DistanceMoments, AProbeAboveAPlaneGathersTheAnalyticMeans) {
  // A plane h below the probe. A ray at cos(theta) = c below the horizon hits at h / c, clamped
  // to the range B; the upper hemisphere misses (B). Over the sphere (d omega = 2 pi dc):
  //   E[d]   = (h (1 + ln(B / h)) + B) / 2,
  //   E[d^2] = (2 B h - h^2 + B^2) / 2.
  const float h = 0.25f;
  ProbeVolume v = one_probe(8);
  const double B = v.moment_range();
  ASSERT_NEAR(B, 1.5 * std::sqrt(12.0), 1e-5);
  FunctionSource plane([h](const Ray& r, Sampler&) {
    PathSample s;
    if (r.direction.z < 0.0f) {
      s.hit = true;
      s.hit_distance = h / -r.direction.z;
    }
    return s;
  });
  UpdateOptions o;
  o.samples = 4096;
  ProbeTracer tracer(plane, o);
  MomentEstimate e(8);
  ddish::sh::ShRgb sh(2);
  tracer.trace_probe(v, 0, 1, sh, nullptr, &e);
  const glm::dvec2 m = sphere_mean(e);
  EXPECT_NEAR(m.x, (h * (1.0 + std::log(B / h)) + B) / 2.0 / B, 2e-3);
  EXPECT_NEAR(m.y, (2.0 * B * h - double(h) * h + B * B) / 2.0 / (B * B), 2e-3);

  // The volume stores each texel's mean on the first update; texels of the upper hemisphere hold
  // exactly (1, 1), and none below it is nearer than h.
  tracer.update(v);
  for (int t = 0; t < v.moment_texels(); ++t) {
    const glm::vec2 s = v.moments(0)[std::size_t(t)];
    EXPECT_GE(s.x, h / B - 1e-6);
    EXPECT_GE(s.y, s.x * s.x - 1e-6);  // a variance is never negative
    EXPECT_LE(s.x, 1.0f);
  }
  EXPECT_EQ(v.moments(0)[moment_texel({0.0f, 0.0f, 1.0f}, 8)], glm::vec2(1.0f));
  const glm::vec2 down = v.moments(0)[moment_texel({0.0f, 0.0f, -1.0f}, 8)];
  EXPECT_LT(down.x, 1.3f * h / B);  // the texel straight down sees the plane at about h
}

TEST(DistanceMoments, AProbeInsideABoxGathersTheAnalyticMeans) {
  // A probe at the centre of a cube of half-size a: the ray toward (x, y, z) hits at
  // a / max(|x|, |y|, |z|). Over one face (z = a), d omega = a dx dy / r^3, so
  //   integral of d = a * I,   integral of d^2 = a^2 * J,
  //   I = integral over [-1,1]^2 of du dv / (1 + u^2 + v^2),
  //   J = integral over [-1,1]^2 of du dv / sqrt(1 + u^2 + v^2),
  // and the sphere means are 6 a I / 4 pi and 6 a^2 J / 4 pi (I, J by a fine midpoint rule).
  const double a = 1.0;
  double I = 0.0, J = 0.0;
  const int n = 2000;
  const double du = 2.0 / n;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double u = -1.0 + (i + 0.5) * du, w = -1.0 + (j + 0.5) * du;
      const double q = 1.0 + u * u + w * w;
      I += du * du / q;
      J += du * du / std::sqrt(q);
    }
  ProbeVolume v = one_probe(4);
  const double B = v.moment_range();
  FunctionSource box([a](const Ray& r, Sampler&) {
    PathSample s;
    s.hit = true;
    const glm::vec3 d = glm::abs(r.direction);
    s.hit_distance = float(a) / std::max(d.x, std::max(d.y, d.z));
    return s;
  });
  UpdateOptions o;
  o.samples = 4096;
  ProbeTracer tracer(box, o);
  MomentEstimate e(4);
  ddish::sh::ShRgb sh(2);
  tracer.trace_probe(v, 0, 1, sh, nullptr, &e);
  const glm::dvec2 m = sphere_mean(e);
  EXPECT_NEAR(m.x * B, 6.0 * a * I / (4.0 * std::numbers::pi), 2e-3);
  EXPECT_NEAR(m.y * B * B, 6.0 * a * a * J / (4.0 * std::numbers::pi), 4e-3);
  // Each texel lies between the faces' nearest and farthest points.
  tracer.update(v);
  for (const glm::vec2& t : v.moments(0)) {
    EXPECT_GE(t.x * B, a - 1e-5);
    EXPECT_LE(t.x * B, std::sqrt(3.0) * a + 1e-5);
  }
}

TEST(DistanceMoments, LaterUpdatesBlendWithTheShWeightAndInactiveProbesReset) {
  // Update 1 sees a wall at 0.5 everywhere, update 2 at 1.0; hysteresis 0.5 per update:
  // the second update's weight is 1 - 0.5 = 0.5, so every texel's mean is 0.75 / B.
  ProbeVolume v = one_probe(2);
  const float B = v.moment_range();
  float dist = 0.5f;
  FunctionSource wall([&dist](const Ray&, Sampler&) {
    PathSample s;
    s.hit = true;
    s.hit_distance = dist;
    return s;
  });
  UpdateOptions o;
  o.samples = 64;
  o.hysteresis = 0.5f;
  ProbeTracer tracer(wall, o);
  tracer.update(v);
  dist = 1.0f;
  tracer.update(v);
  for (const glm::vec2& t : v.moments(0)) {
    EXPECT_NEAR(t.x * B, 0.75f, 1e-5f);
    EXPECT_NEAR(t.y * B * B, 0.5f * 0.25f + 0.5f * 1.0f, 1e-5f);
  }
  v.deactivate(0, false);
  for (const glm::vec2& t : v.moments(0)) EXPECT_EQ(t, glm::vec2(1.0f));
}
