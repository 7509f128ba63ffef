// Frustum planes in Vulkan clip conventions and the probe priorities built on them.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "probes/frustum.h"
#include "probes/priority.h"

using namespace ddish::probes;
using ddish::scene::Aabb;
using ddish::scene::View;
using ddish::scene::look_at_view;

namespace {

constexpr float kFov = std::numbers::pi_v<float> / 3.0f;  // 60 degrees vertical

// Eye at the origin looking down -z, 640x480, near 0.1, far 100.
View forward_view(const glm::vec3& eye = glm::vec3(0.0f)) {
  return look_at_view(eye, eye + glm::vec3(0.0f, 0.0f, -1.0f), {0.0f, 1.0f, 0.0f}, kFov, 640, 480,
                      0.1f, 100.0f);
}

// A row of 20 probes along z from -19 to 19 (spacing 2 along z, 1 across), all active and
// updated once, `age` frames ago.
ProbeVolume probe_row(std::uint32_t age) {
  ProbeVolume v(ProbeGrid(Aabb{{-0.5f, -0.5f, -20.0f}, {0.5f, 0.5f, 20.0f}}, {1, 1, 20}));
  for (std::uint32_t i = 0; i < v.probe_count(); ++i) {
    ProbeState& s = v.state(i);
    s.flags = 0;
    s.updates = 1;
    s.samples = 64;
    s.age = age;
  }
  return v;
}

std::uint32_t probe_at_z(const ProbeVolume& v, float z) {
  return std::uint32_t(std::lround(v.grid().grid_coordinate({0.0f, 0.0f, z}).z));
}

}  // namespace

TEST(Frustum, PlanesAreSignedDistancesInMetres) {
  Frustum f(forward_view());
  // Near plane z = -0.1 facing -z; far plane z = -100 facing +z.
  EXPECT_NEAR(f.planes()[4].distance({0.0f, 0.0f, -5.0f}), 4.9f, 1e-4f);
  EXPECT_NEAR(f.planes()[5].distance({0.0f, 0.0f, -5.0f}), 95.0f, 1e-2f);
  // Side planes pass through the eye at half the field of view: a point on the axis at depth
  // 5 is 5 sin(30 deg) = 2.5 m from the top and bottom planes.
  EXPECT_NEAR(f.planes()[2].distance({0.0f, 0.0f, -5.0f}), 2.5f, 1e-4f);
  EXPECT_NEAR(f.planes()[3].distance({0.0f, 0.0f, -5.0f}), 2.5f, 1e-4f);
  for (const Plane& p : f.planes()) EXPECT_NEAR(glm::length(p.normal), 1.0f, 1e-5f);

  EXPECT_TRUE(f.contains({0.0f, 0.0f, -5.0f}));
  EXPECT_FALSE(f.contains({0.0f, 0.0f, 5.0f}));      // behind
  EXPECT_FALSE(f.contains({0.0f, 0.0f, -150.0f}));   // past the far plane
  // Horizontal half-extent at depth 5: 5 tan(30 deg) * 4/3 = 3.85 m; vertical 2.89 m.
  EXPECT_TRUE(f.contains({3.7f, 0.0f, -5.0f}));
  EXPECT_FALSE(f.contains({4.0f, 0.0f, -5.0f}));
  EXPECT_TRUE(f.contains({0.0f, 2.8f, -5.0f}));
  EXPECT_FALSE(f.contains({0.0f, -3.0f, -5.0f}));
}

TEST(Frustum, BoxesAndMargin) {
  Frustum f(forward_view());
  EXPECT_TRUE(f.intersects(Aabb{{-1.0f, -1.0f, -6.0f}, {1.0f, 1.0f, -4.0f}}));
  // A box straddling the near plane and one straddling a side plane meet the frustum.
  EXPECT_TRUE(f.intersects(Aabb{{-1.0f, -1.0f, -1.0f}, {1.0f, 1.0f, 1.0f}}));
  EXPECT_TRUE(f.intersects(Aabb{{3.5f, -0.5f, -5.5f}, {6.0f, 0.5f, -4.5f}}));
  // Entirely behind the eye: 0.3 m behind the near plane at its closest.
  const Aabb behind{{-1.0f, -1.0f, 0.2f}, {1.0f, 1.0f, 2.0f}};
  EXPECT_FALSE(f.intersects(behind));
  EXPECT_FALSE(f.intersects(behind, 0.25f));
  EXPECT_TRUE(f.intersects(behind, 0.35f));  // within the motion margin
  EXPECT_FALSE(f.intersects(Aabb{}));       // empty
}

TEST(Priority, InFrontBeatsBehindEveryView) {
  ProbeVolume v = probe_row(5);
  // Two views (a stereo pair) looking down -z from z = 0.
  std::vector<View> views{forward_view({-0.03f, 0.0f, 0.0f}), forward_view({0.03f, 0.0f, 0.0f})};
  ProbePriorities p = compute_priorities(v, views, PriorityOptions{});
  const std::uint32_t front = probe_at_z(v, -9.0f), behind = probe_at_z(v, 9.0f);
  EXPECT_TRUE(p.in_view[front]);
  EXPECT_FALSE(p.in_view[behind]);
  EXPECT_GT(p.priority[front], p.priority[behind]);
  EXPECT_EQ(p.priority[front].tier, 0);
  // Detail: a 2 m cell at 9 m, 480 pixels over 2 tan(30 deg): 2 / 9 * 240 / tan(30 deg).
  const float pixels = 2.0f / std::hypot(9.0f, 0.03f) * 240.0f / std::tan(kFov / 2.0f);
  EXPECT_NEAR(p.pixels[front], pixels, 0.01f * pixels);
  EXPECT_FLOAT_EQ(p.pixels[behind], 0.0f);
  // priority = (age + 1) * importance: in view 1 + pixels / 32, out of view 1 / max_age.
  EXPECT_NEAR(p.priority[front].value, 6.0f * (1.0f + p.pixels[front] / 32.0f), 1e-3f);
  EXPECT_NEAR(p.priority[behind].value, 6.0f / 30.0f, 1e-6f);
  // Nearer probes in view rank higher at equal age.
  EXPECT_GT(p.priority[probe_at_z(v, -3.0f)], p.priority[front]);
  // Probes behind: z >= 3 with a 2 m influence box and a 0.5 m margin stay out (z = 1 is in:
  // its box reaches z = -1).
  for (float z = 3.0f; z < 20.0f; z += 2.0f) EXPECT_FALSE(p.in_view[probe_at_z(v, z)]) << z;
  EXPECT_TRUE(p.in_view[probe_at_z(v, 1.0f)]);
  EXPECT_EQ(p.in_view_count, 11u);
  EXPECT_EQ(p.active, 20u);
}

TEST(Priority, TiersOverdueFreshInactive) {
  ProbeVolume v = probe_row(3);
  PriorityOptions o;
  o.max_age = 10;
  const std::uint32_t stale_behind = probe_at_z(v, 15.0f), fresh = probe_at_z(v, 13.0f),
                      dead = probe_at_z(v, -5.0f), seen = probe_at_z(v, -3.0f);
  v.state(stale_behind).age = 10;
  v.state(fresh).updates = 0;
  v.state(fresh).samples = 0;
  v.deactivate(dead, true);
  std::vector<View> views{forward_view()};
  ProbePriorities p = compute_priorities(v, views, o);
  EXPECT_EQ(p.priority[stale_behind].tier, 2);
  EXPECT_EQ(p.priority[fresh].tier, 1);
  EXPECT_GT(p.priority[stale_behind], p.priority[fresh]);
  EXPECT_GT(p.priority[fresh], p.priority[seen]);  // no light beats some light
  EXPECT_FALSE(p.candidate[dead]);
  EXPECT_EQ(p.active, 19u);
  EXPECT_EQ(p.overdue, 1u);
  EXPECT_EQ(p.fresh, 1u);
  // A probe out of view one frame short of max_age ranks with a just-updated visible one of
  // vanishing size: (9 + 1) / 10 = 1.
  v.state(stale_behind).age = 9;
  p = compute_priorities(v, views, o);
  EXPECT_FLOAT_EQ(p.priority[stale_behind].value, 1.0f);
}

TEST(Priority, NoViewsMeansNothingInViewAndBadOptionsThrow) {
  ProbeVolume v = probe_row(1);
  ProbePriorities p = compute_priorities(v, {}, PriorityOptions{});
  EXPECT_EQ(p.in_view_count, 0u);
  EXPECT_THROW(compute_priorities(v, {}, PriorityOptions{.margin = -1.0f}), std::invalid_argument);
  EXPECT_THROW(compute_priorities(v, {}, PriorityOptions{.max_age = 0}), std::invalid_argument);
  View no_pixels = forward_view();
  no_pixels.height = 0;
  std::vector<View> views{no_pixels};
  EXPECT_THROW(compute_priorities(v, views, PriorityOptions{}), std::invalid_argument);
}
