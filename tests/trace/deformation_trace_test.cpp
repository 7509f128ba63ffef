// A skinned mesh in the Embree scene follows Scene::pose: built at the rest pose, refitted after
// pose(1) bends scenes/skinned_bar.gltf's upper half to -x. Rays through where the half was
// then miss and rays through where it went hit, at the analytic distance.
#include <filesystem>
#include <vector>

#include <gtest/gtest.h>

#include "scene/gltf_loader.h"
#include "scene/scene.h"
#include "trace/embree_scene.h"
#include "trace/texture_lookup.h"

namespace ddish::trace {
namespace {

TEST(Deformation, EmbreeSceneRefitsTheSkinnedBar) {
  scene::Scene s = scene::load_scene(
      (std::filesystem::path(DDISH_SOURCE_DIR) / "scenes" / "skinned_bar.gltf").string());
  const TextureSet textures(s);
  EmbreeScene embree(s, textures);
  // Rays along -z from z = 5: the bar's front faces are at z = 0.1.
  const Ray upper{{0.0f, 1.5f, 5.0f}, {0.0f, 0.0f, -1.0f}};  // the upright upper half
  const Ray arm{{-0.6f, 1.0f, 5.0f}, {0.0f, 0.0f, -1.0f}};   // the bent one
  const Ray lower{{0.0f, 0.5f, 5.0f}, {0.0f, 0.0f, -1.0f}};  // the lower half, never moves
  Hit hit;
  EXPECT_TRUE(embree.intersect(upper, {}, hit));
  EXPECT_FALSE(embree.intersect(arm, {}, hit));

  const std::vector<int> moved = s.pose(1.0);
  embree.update(s, moved);
  EXPECT_FALSE(embree.intersect(upper, {}, hit));
  ASSERT_TRUE(embree.intersect(arm, {}, hit));
  EXPECT_NEAR(hit.t, 4.9f, 1e-4f);
  ASSERT_TRUE(embree.intersect(lower, {}, hit));
  EXPECT_NEAR(hit.t, 4.9f, 1e-4f);

  s.pose(0.0);  // and back
  embree.update(s, std::vector<int>{0});
  EXPECT_TRUE(embree.intersect(upper, {}, hit));
  EXPECT_FALSE(embree.intersect(arm, {}, hit));
}

}  // namespace
}  // namespace ddish::trace
