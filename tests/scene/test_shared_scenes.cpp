// The benchmark scenes in ../shared/scenes (skipped where absent): the triangle counts after
// instancing that ../shared/scenes/README.md lists, and their sidecars.
#include <gtest/gtest.h>

#include <filesystem>

#include "scene/features.h"
#include "scene/gltf_loader.h"

using namespace ddish;

namespace {

std::string shared_scene(const char* rel) {
  return (std::filesystem::path(DDISH_SOURCE_DIR) / ".." / "shared" / "scenes" / rel).string();
}

scene::Scene load_headers_only(const std::string& path) {
  scene::LoadOptions opt;
  opt.decode_textures = false;
  return scene::load_scene(path, opt);
}

}  // namespace

TEST(SharedScenes, Sponza) {
  std::string path = shared_scene("sponza/Sponza.gltf");
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "no " << path;
  scene::Scene s = load_headers_only(path);
  EXPECT_EQ(s.triangle_count(), 262087u);
  EXPECT_EQ(s.textures.size(), 49u);
  EXPECT_GT(s.textures[0].width, 0);
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].type, scene::LightType::Directional);
  EXPECT_FLOAT_EQ(s.lights[0].intensity, 10.0f);
  EXPECT_LT(s.lights[0].direction.y, 0.0f);  // the sun shines down
  EXPECT_EQ(s.cameras.size(), 4u);
  ASSERT_NE(s.default_camera(), nullptr);
  EXPECT_EQ(s.default_camera()->name, "CameraMain");
  ASSERT_TRUE(s.sidecar.probe_counts.has_value());
  EXPECT_EQ(*s.sidecar.probe_counts, glm::ivec3(16, 8, 8));
  scene::RenderPlan plan = scene::make_plan(scene::analyze(s));
  EXPECT_TRUE(plan.shadow_maps);
  EXPECT_TRUE(plan.alpha_test);
  EXPECT_TRUE(plan.texture_sampling);
  EXPECT_FALSE(plan.point_shadows);
}

TEST(SharedScenes, BreakfastRoom) {
  std::string path = shared_scene("breakfast_room/BreakfastRoom.gltf");
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "no " << path;
  scene::Scene s = load_headers_only(path);
  EXPECT_EQ(s.triangle_count(), 262687u);
  EXPECT_EQ(s.cameras.size(), 3u);
  ASSERT_TRUE(s.sidecar.probe_counts.has_value());
  EXPECT_EQ(*s.sidecar.probe_counts, glm::ivec3(8, 4, 8));
}
