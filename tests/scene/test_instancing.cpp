// EXT_mesh_gpu_instancing (scene/gltf_instancing.cpp): scenes/instanced_boxes.gltf draws one
// 0.4 m cube three times under a node at (0, 1, 0): at (-1, 0.2, 0); at (0, 0.2, 0) turned 45
// degrees about +Y; at (1, 0.4, 0) twice the size (scripts/make_scenes.py).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "gltf_builder.h"
#include "scene/gltf_loader.h"
#include "scene/load_error.h"

using namespace ddish;

namespace {

void expect_near(const glm::vec3& v, const glm::vec3& want) {
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(v[i], want[i], 1e-5f) << "component " << i;
}

}  // namespace

TEST(Instancing, EveryInstanceBecomesASceneInstance) {
  const scene::Scene s =
      scene::load_scene(std::string(DDISH_SOURCE_DIR) + "/scenes/instanced_boxes.gltf");
  ASSERT_EQ(s.instances.size(), 3u);
  EXPECT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.triangle_count(), 36u);
  for (const std::string& w : s.warnings) EXPECT_EQ(w.find("EXT_mesh_gpu_instancing"), std::string::npos) << w;
  // Each instance's world transform is the node's translation times its own TRS.
  expect_near(glm::vec3(s.instances[0].transform[3]), {-1.0f, 1.2f, 0.0f});
  expect_near(glm::vec3(s.instances[2].transform * glm::vec4(0.2f, 0.2f, 0.2f, 1.0f)),
              {1.4f, 1.8f, 0.4f});
  // The turned cube's corner (0.2, y, 0.2) lies on +x at 0.2 sqrt(2).
  expect_near(glm::vec3(s.instances[1].transform * glm::vec4(0.2f, 0.0f, 0.2f, 1.0f)),
              {0.2f * std::sqrt(2.0f), 1.2f, 0.0f});
  const scene::Aabb b = s.bounds();
  expect_near(b.min, {-1.2f, 1.0f, -0.4f});
  expect_near(b.max, {1.4f, 1.8f, 0.4f});
}

TEST(Instancing, InstancesFollowTheirNode) {
  scene::Scene s = scene::load_scene(std::string(DDISH_SOURCE_DIR) + "/scenes/instanced_boxes.gltf");
  s.nodes[std::size_t(s.instances[0].node)].translation = glm::vec3(0.0f, 3.0f, 0.0f);
  const std::vector<int> moved = s.pose(0.0);
  EXPECT_EQ(moved.size(), 3u);
  expect_near(glm::vec3(s.instances[0].transform[3]), {-1.0f, 3.2f, 0.0f});
}

TEST(Instancing, MismatchedAttributeCountsAreRejected) {
  test::TempDir dir("instancing_bad");
  test::GltfBuilder b;
  const int mesh = b.add_quad_mesh();
  const int t = b.add_floats({0, 0, 0, 1, 0, 0}, "VEC3", 2);
  const int sc = b.add_floats({1, 1, 1}, "VEC3", 1);
  b.doc["extensionsUsed"] = {"EXT_mesh_gpu_instancing"};
  b.add_node({{"mesh", mesh},
              {"extensions",
               {{"EXT_mesh_gpu_instancing", {{"attributes", {{"TRANSLATION", t}, {"SCALE", sc}}}}}}}});
  const std::string path = b.write(dir.path.string(), "i.gltf", test::BufferMode::External);
  try {
    scene::load_scene(path);
    FAIL() << "loaded";
  } catch (const scene::LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("different instance counts"), std::string::npos) << e.what();
  }
}
