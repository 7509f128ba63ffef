// scenes/cornell_light.gltf through the path tracer: the point light jumps (STEP keys) and is
// switched off by a move into a closed housing outside the room. Tracer::update after pose()
// must follow both although no instance moves: light from the new place, none from the housing
// (the same, within noise, as intensity 0), and the old figures back when the light returns.
#include <filesystem>
#include <vector>

#include <gtest/gtest.h>

#include "scene/gltf_loader.h"
#include "scene/scene.h"
#include "trace/tracer.h"
#include "trace_test_scenes.h"

namespace ddish::trace {
namespace {

TEST(DynamicLight, TracerFollowsMovedAndHousedPointLight) {
  scene::Scene s = scene::load_scene(
      (std::filesystem::path(DDISH_SOURCE_DIR) / "scenes" / "cornell_light.gltf").string());
  ASSERT_EQ(s.lights.size(), 1u);
  PathOptions opt;
  opt.max_bounces = 2;
  Tracer tracer(s, opt);
  // Looking down at the floor under light A (x < 0, z > 0) from 1 m up.
  const Ray down{{-0.5f, 1.0f, 0.45f}, {0, -1, 0}};
  const int n = 3000;
  auto at = [&](double t) {
    const std::vector<int> moved = s.pose(t);
    EXPECT_TRUE(moved.empty());
    tracer.update(s, moved);
    return testing::estimate(tracer, down, n);
  };
  const testing::Estimate a = at(1.0);    // light A, right above
  const testing::Estimate b = at(5.0);    // light B, across the room
  const testing::Estimate off = at(15.0);  // in the housing: only the ceiling quad lights
  const testing::Estimate again = at(25.0);  // B again
  EXPECT_GT(a.mean.x, 1.5 * b.mean.x);
  EXPECT_GT(b.mean.x, off.mean.x + 4.0 * std::hypot(b.stderr_.x, off.stderr_.x));
  EXPECT_NEAR(again.mean.x, b.mean.x, 1e-9 * b.mean.x);  // same state, same samples
  // Off by the housing is off: the light at A with intensity 0 gives the same, within noise.
  s.pose(1.0);
  s.lights[0].intensity = 0.0f;
  tracer.update(s, {});
  const testing::Estimate zero = testing::estimate(tracer, down, n, 11);
  EXPECT_NEAR(off.mean.x, zero.mean.x, 4.0 * std::hypot(off.stderr_.x, zero.stderr_.x));
  EXPECT_GT(off.mean.x, 0.0);  // the fill light is still on
}

}  // namespace
}  // namespace ddish::trace
