// Skins and morph targets posed by Scene::pose, against analytic figures: scenes/skinned_bar.gltf
// (a bar bent 90 degrees at its middle joint), scenes/morph_panels.gltf (a morph target at
// weight 0.5, by default and from a "weights" channel), and small files built here for the
// rules (weights that do not sum to 1, node weights over mesh weights, bad skins).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>

#include "gltf_builder.h"
#include "scene/gltf_loader.h"
#include "scene/scene.h"

using namespace ddish;

namespace {

std::string shipped(const char* name) {
  return (std::filesystem::path(DDISH_SOURCE_DIR) / "scenes" / name).string();
}

void expect_box(const scene::Aabb& box, glm::vec3 min, glm::vec3 max, const char* what) {
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(box.min[k], min[k], 1e-5f) << what << " min " << k;
    EXPECT_NEAR(box.max[k], max[k], 1e-5f) << what << " max " << k;
  }
}

}  // namespace

// The bar's halves are rigid: the upper one turns about the elbow (0, 1, 0). At angle a its far
// corners reach x = -(0.1 cos a + sin a) and y = 1 + 0.1 sin a + cos a; the lower half bounds
// x <= 0.1 and y >= 0. The mesh node's x = 3 does not move it (glTF ignores a skinned mesh's
// node transform: the joint matrices cancel it).
TEST(Skinning, BentBarHasAnalyticBounds) {
  scene::Scene s = scene::load_scene(shipped("skinned_bar.gltf"));
  ASSERT_EQ(s.skins.size(), 1u);
  ASSERT_EQ(s.deformed.size(), 1u);
  EXPECT_EQ(s.deformed[0].skin, 0);
  for (const std::string& w : s.warnings) EXPECT_EQ(w.find("skin"), std::string::npos) << w;
  expect_box(s.bounds(), {-0.1f, 0.0f, -0.1f}, {0.1f, 2.0f, 0.1f}, "rest (t = 0)");

  const scene::Mesh& bar = s.meshes[std::size_t(s.deformed[0].mesh)];
  const std::uint64_t version = bar.pose_version;
  const std::vector<int> moved = s.pose(1.0);  // 90 degrees
  ASSERT_EQ(moved.size(), 1u);  // the bar's node does not move, its vertices do
  EXPECT_EQ(bar.pose_version, version + 1);
  expect_box(s.bounds(), {-1.0f, 0.0f, -0.1f}, {0.1f, 1.1f, 0.1f}, "bent (t = 1)");
  // The upper half's top face pointed +Y; it now points -X (normals follow the joints).
  int turned = 0;
  for (std::size_t v = 0; v < bar.positions.size(); ++v) {
    if (bar.deformation.rest_normals[v] != glm::vec3(0.0f, 1.0f, 0.0f) ||
        bar.deformation.rest_positions[v].y != 2.0f)
      continue;
    const glm::vec3 world = glm::vec3(s.instances[0].transform * glm::vec4(bar.positions[v], 1.0f));
    EXPECT_NEAR(world.x, -1.0f, 1e-5f) << "vertex " << v;
    EXPECT_NEAR(bar.normals[v].x, -1.0f, 1e-5f) << "vertex " << v;
    EXPECT_NEAR(bar.normals[v].y, 0.0f, 1e-5f) << "vertex " << v;
    ++turned;
  }
  EXPECT_EQ(turned, 4);

  const float a = 0.78539816f;  // 45 degrees at t = 0.5 (slerp halfway)
  s.pose(0.5);
  expect_box(s.bounds(), {-(0.1f * std::cos(a) + std::sin(a)), 0.0f, -0.1f},
             {0.1f, 1.0f + 0.1f * std::sin(a) + std::cos(a), 0.1f}, "t = 0.5");
  EXPECT_TRUE(s.pose(0.5).empty());  // same pose: nothing to re-upload
  EXPECT_EQ(bar.pose_version, version + 2);
}

// One mesh drawn by two nodes becomes two meshes (each node poses its own). The left keeps the
// mesh's weight 0.5; the right's channel runs 0 -> 1 over 2 s. The target lifts the top edge by
// 1 and adds (0, 2, 0) to the normal (0, 0, 1): at weight 0.5, normalize(0, 1, 1).
TEST(Morph, WeightHalfMovesHalfway) {
  scene::Scene s = scene::load_scene(shipped("morph_panels.gltf"));
  ASSERT_EQ(s.instances.size(), 2u);
  ASSERT_EQ(s.deformed.size(), 2u);
  EXPECT_NE(s.instances[0].mesh, s.instances[1].mesh);
  ASSERT_EQ(s.animations.size(), 1u);
  const scene::AnimChannel& ch = s.animations[0].channels.at(0);
  EXPECT_EQ(ch.path, scene::AnimPath::Weights);
  EXPECT_FLOAT_EQ(ch.sample(0.5f).x, 0.25f);
  EXPECT_FLOAT_EQ(ch.sample(1.0f).x, 0.5f);

  auto top = [&](int instance) {
    const scene::Mesh& m = s.meshes[std::size_t(s.instances[std::size_t(instance)].mesh)];
    return m.bounds.max.y;
  };
  const int left = s.nodes[std::size_t(s.instances[0].node)].name == "Default" ? 0 : 1;
  const int right = 1 - left;
  s.pose(1.0);
  EXPECT_FLOAT_EQ(top(left), 1.5f);
  EXPECT_FLOAT_EQ(top(right), 1.5f);
  const float r = std::sqrt(0.5f);
  for (const scene::Instance& inst : s.instances)
    for (const glm::vec3& n : s.meshes[std::size_t(inst.mesh)].normals) {
      EXPECT_NEAR(n.y, r, 1e-6f);
      EXPECT_NEAR(n.z, r, 1e-6f);
    }
  const std::vector<int> moved = s.pose(0.5);
  ASSERT_EQ(moved.size(), 1u);
  EXPECT_EQ(moved[0], right);
  EXPECT_FLOAT_EQ(top(left), 1.5f);
  EXPECT_FLOAT_EQ(top(right), 1.25f);
}

namespace {

// A one-triangle mesh skinned to joints of `joint_count` nodes (each at x = 2 · (index + 1),
// inverse bind matrices identity), its vertices' JOINTS_0 / WEIGHTS_0 given, and optionally a
// node weight over a morph target (lifting y by 1) with mesh weight 0.25.
struct SkinFile {
  std::vector<std::uint8_t> joints = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  std::vector<float> weights = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
  std::vector<std::uint8_t> joints1;  // JOINTS_1 / WEIGHTS_1 when not empty
  std::vector<float> weights1;
  int joint_count = 1;
  bool morph = false;
  std::string write(const test::TempDir& dir) const {
    test::GltfBuilder b;
    nlohmann::json prim;
    prim["attributes"]["POSITION"] = b.add_floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
    const int view = b.add_view(joints.data(), joints.size());
    b.doc["accessors"].push_back(
        {{"bufferView", view}, {"componentType", 5121}, {"count", 3}, {"type", "VEC4"}});
    prim["attributes"]["JOINTS_0"] = int(b.doc["accessors"].size()) - 1;
    prim["attributes"]["WEIGHTS_0"] = b.add_floats(weights, "VEC4", 3);
    if (!joints1.empty()) {
      const int view1 = b.add_view(joints1.data(), joints1.size());
      b.doc["accessors"].push_back(
          {{"bufferView", view1}, {"componentType", 5121}, {"count", 3}, {"type", "VEC4"}});
      prim["attributes"]["JOINTS_1"] = int(b.doc["accessors"].size()) - 1;
      prim["attributes"]["WEIGHTS_1"] = b.add_floats(weights1, "VEC4", 3);
    }
    if (morph) prim["targets"] = {{{"POSITION", b.add_floats({0, 1, 0, 0, 1, 0, 0, 1, 0}, "VEC3", 3)}}};
    nlohmann::json mesh = {{"primitives", {prim}}};
    if (morph) mesh["weights"] = {0.25};
    b.doc["meshes"].push_back(mesh);
    nlohmann::json skin = {{"joints", nlohmann::json::array()}};
    for (int j = 0; j < joint_count; ++j)
      skin["joints"].push_back(b.add_node({{"translation", {2.0 * (j + 1), 0, 0}}}));
    b.doc["skins"].push_back(skin);
    nlohmann::json node = {{"mesh", 0}, {"skin", 0}};
    if (morph) node["weights"] = {1.0};
    b.add_node(node);
    return b.write(dir.path.string(), "skin.gltf", test::BufferMode::External);
  }
};

}  // namespace

// glTF asks for weights that sum to 1; files round them, so ddish divides by the sum: a vertex
// with weight 0.25 on one joint moves with that joint entirely. Weights all 0 leave a vertex
// where it is. Node weights (1) win over mesh weights (0.25).
TEST(Skinning, WeightsAreNormalisedAndZeroWeightsStay) {
  test::TempDir dir("skin_weights");
  SkinFile f;
  f.weights = {0.25f, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0};
  f.morph = true;
  scene::Scene s = scene::load_scene(f.write(dir));
  ASSERT_EQ(s.deformed.size(), 1u);
  const scene::Mesh& m = s.meshes[std::size_t(s.deformed[0].mesh)];
  const glm::mat4& xf = s.instances[0].transform;
  auto world = [&](int v) { return glm::vec3(xf * glm::vec4(m.positions[std::size_t(v)], 1.0f)); };
  EXPECT_FLOAT_EQ(world(0).x, 2.0f);  // moved by the joint at x = 2 (weight 0.25 -> 1)
  EXPECT_FLOAT_EQ(world(0).y, 1.0f);  // the morph target at node weight 1
  EXPECT_FLOAT_EQ(world(1).x, 1.0f);  // weights all 0: where the file put it
  EXPECT_FLOAT_EQ(world(2).x, 2.0f);
  EXPECT_FLOAT_EQ(world(2).y, 2.0f);
}

// A second set of influences (JOINTS_1 / WEIGHTS_1) counts like the first: vertex 0 has
// weight 0.5 on the joint at x = 2 (set 0) and 0.5 on the one at x = 4 (set 1), so it lands
// at x = 3.
TEST(Skinning, EightInfluencesPerVertex) {
  test::TempDir dir("skin_eight");
  SkinFile f;
  f.joint_count = 2;
  f.weights = {0.5f, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
  f.joints1 = {1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  f.weights1 = {0.5f, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  scene::Scene s = scene::load_scene(f.write(dir));
  ASSERT_EQ(s.deformed.size(), 1u);
  const scene::Mesh& m = s.meshes[std::size_t(s.deformed[0].mesh)];
  EXPECT_EQ(m.deformation.influences.sets, 2);
  const glm::vec3 p = glm::vec3(s.instances[0].transform * glm::vec4(m.positions[0], 1.0f));
  EXPECT_FLOAT_EQ(p.x, 3.0f);
  EXPECT_FLOAT_EQ(glm::vec3(s.instances[0].transform * glm::vec4(m.positions[1], 1.0f)).x, 3.0f);
}

TEST(Skinning, BadSkinsGetOneClearError) {
  test::TempDir dir("skin_bad");
  SkinFile out_of_range;
  out_of_range.joints = {0, 0, 0, 0, 5, 0, 0, 0, 0, 0, 0, 0};
  out_of_range.joint_count = 2;
  EXPECT_NE(test::load_message(out_of_range.write(dir)).find("vertex 1 uses joint 5, but the skin has 2 joints"),
            std::string::npos)
      << test::load_message(out_of_range.write(dir));
  // A joint out of range with weight 0 is never read: the file loads.
  SkinFile unused = out_of_range;
  unused.weights = {1, 0, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0};
  EXPECT_EQ(test::load_message(unused.write(dir)), "(loaded)");
  SkinFile none;
  none.joint_count = 0;
  EXPECT_NE(test::load_message(none.write(dir)).find("has no joints"), std::string::npos)
      << test::load_message(none.write(dir));
  SkinFile negative;
  negative.weights[4] = -0.5f;
  EXPECT_NE(test::load_message(negative.write(dir)).find("vertex 1 has a negative weight"), std::string::npos)
      << test::load_message(negative.write(dir));
}

// Morph targets may all name one accessor: 100000 targets of 2^20 vertices ask for 1172 GiB of
// deltas from a file of 3.8 MB. The load stops with one line before reading any.
TEST(Morph, TargetsBeyondMemoryAreRefusedBeforeTheyAreRead) {
  test::TempDir dir("morph_memory");
  test::GltfBuilder b;
  b.doc["accessors"].push_back({{"componentType", 5126}, {"count", 1 << 20}, {"type", "VEC3"}});
  nlohmann::json prim;
  prim["attributes"]["POSITION"] = 0;
  prim["targets"] = nlohmann::json::array();
  for (int k = 0; k < 100000; ++k) prim["targets"].push_back({{"POSITION", 0}});
  b.doc["meshes"].push_back({{"primitives", {prim}}});
  b.add_node({{"mesh", 0}});
  const std::string message =
      test::load_message(b.write(dir.path.string(), "m.gltf", test::BufferMode::External));
  EXPECT_NE(message.find("its 100000 morph targets of 1048576 vertices need 1171.9 GiB, more than the"),
            std::string::npos)
      << message;
}
