// The GPU tracer's scene layout, without a device: the environment map's tables are
// trace::EnvironmentLight's, and a deformed mesh's vertices follow its pose (only when it changed).
#include <string>

#include <gtest/gtest.h>

#include "scene/gltf_loader.h"
#include "scene/scene.h"
#include "test_environment.h"
#include "trace/environment_light.h"
#include "trace_vk/scene_layout.h"

namespace ddish::trace_vk::test {
namespace {

TEST(SceneLayout, EnvironmentTablesAreTheCpuLightsInFloats) {
  scene::Scene s;
  s.environment_map = test_environment_map();
  const SceneLayout layout = SceneLayout::build(s);
  const trace::EnvironmentLight light(s.environment_map);
  const trace::EnvironmentTables t = light.tables();
  ASSERT_EQ(layout.environment.width, 32u);
  ASSERT_EQ(layout.environment.height, 16u);
  EXPECT_FLOAT_EQ(layout.environment.cos_rotation, std::cos(glm::radians(40.0f)));
  EXPECT_FLOAT_EQ(layout.environment.sin_rotation, std::sin(glm::radians(40.0f)));
  ASSERT_EQ(layout.environment_texels.size(), 32u * 16u);
  ASSERT_EQ(layout.environment_cdf.size(), 17u + 16u * 33u);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 32; ++x) {
      const glm::vec4& g = layout.environment_texels[std::size_t(y) * 32 + std::size_t(x)];
      EXPECT_EQ(glm::vec3(g), s.environment_map->texel(x, y));  // the intensity already applied
      EXPECT_FLOAT_EQ(g.w, float(light.texel_probability(x, y) * 32 * 16)) << x << ", " << y;
    }
  for (std::size_t i = 0; i < t.row_cdf.size(); ++i) EXPECT_FLOAT_EQ(layout.environment_cdf[i], float(t.row_cdf[i]));
  for (std::size_t i = 0; i < t.column_cdf.size(); ++i)
    EXPECT_FLOAT_EQ(layout.environment_cdf[t.row_cdf.size() + i], float(t.column_cdf[i]));
}

TEST(SceneLayout, ABlackEnvironmentMapLightsNothing) {
  scene::Scene s;
  s.environment_map = std::make_shared<const scene::EnvironmentMap>(
      scene::make_environment_map(4, 2, std::vector<glm::vec3>(8, glm::vec3(0.0f)), 0.0f, 1.0f, "black"));
  const SceneLayout layout = SceneLayout::build(s);
  EXPECT_EQ(layout.environment.width, 0u);
  EXPECT_TRUE(layout.environment_texels.empty());
}

TEST(SceneLayout, ADeformedMeshsVerticesFollowItsPoseOnlyWhenItChanged) {
  scene::Scene s = scene::load_scene(std::string(DDISH_SOURCE_DIR) + "/scenes/skinned_bar.gltf");
  ASSERT_EQ(s.deformed.size(), 1u);
  const auto m = static_cast<std::size_t>(s.deformed[0].mesh);
  SceneLayout layout = SceneLayout::build(s);
  EXPECT_TRUE(layout.deformed[m]);
  EXPECT_TRUE(layout.repose(s).empty());  // built at this pose
  s.pose(1.0);                            // the upper half turns 90 degrees
  const std::vector<std::uint32_t> changed = layout.repose(s);
  ASSERT_EQ(changed, std::vector<std::uint32_t>{std::uint32_t(m)});
  const scene::Mesh& mesh = s.meshes[m];
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    const GpuVertex& g = layout.vertices[layout.meshes[m].first_vertex + v];
    EXPECT_EQ(glm::vec3(g.position_u), mesh.positions[v]) << v;
    EXPECT_EQ(glm::vec3(g.normal_v), mesh.normals[v]) << v;
    EXPECT_EQ(g.tangent, mesh.tangents[v]) << v;
  }
  EXPECT_TRUE(layout.repose(s).empty());
  s.pose(1.0);  // the same pose again: pose() leaves the mesh, and so does repose
  EXPECT_TRUE(layout.repose(s).empty());
}

}  // namespace
}  // namespace ddish::trace_vk::test
