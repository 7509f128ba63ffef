// What the loader reads from the feature scenes of scripts/feature_scenes.py: COLOR_0 in its three
// encodings, TEXCOORD_1 and KHR_texture_transform per slot, sampler filters, the dielectric
// layer's extensions, and MikkTSpace tangents on a file without TANGENT.
#include <gtest/gtest.h>

#include <cmath>

#include "scene/features.h"
#include "scene/gltf_loader.h"

using namespace ddish;

namespace {

scene::Scene bundled(const char* name) {
  return scene::load_scene(std::string(DDISH_SOURCE_DIR) + "/scenes/" + name);
}

TEST(GltfFeatures, VertexColoursInEveryEncoding) {
  const scene::Scene s = bundled("vertex_colors.gltf");
  ASSERT_EQ(s.meshes.size(), 3u);
  // Vertex 0 of each panel is its left edge (feature_scenes.panel: x0 first).
  const scene::Mesh& f = s.meshes[0];  // float RGB: alpha 1 added
  ASSERT_EQ(f.colors.size(), f.positions.size());
  const scene::Mesh& u8 = s.meshes[1];
  const scene::Mesh& u16 = s.meshes[2];
  for (std::size_t v = 0; v < 4; ++v) {
    const bool left = f.positions[v].x < 0.0f;
    EXPECT_EQ(f.colors[v], left ? glm::vec4(1, 0, 0, 1) : glm::vec4(0, 0, 1, 1)) << v;
    // unorm8: 51 / 255 = 0.2 and 102 / 255 = 0.4 exactly in the codes' meaning.
    const glm::vec4 want8 = left ? glm::vec4(0, 1, 51.0f / 255.0f, 1) : glm::vec4(1, 102.0f / 255.0f, 0, 1);
    for (int k = 0; k < 4; ++k) EXPECT_FLOAT_EQ(u8.colors[v][k], want8[k]) << v;
    const glm::vec4 want16 = left ? glm::vec4(13107, 26214, 39321, 65535) / 65535.0f
                                  : glm::vec4(52428, 39321, 26214, 65535) / 65535.0f;
    for (int k = 0; k < 4; ++k) EXPECT_FLOAT_EQ(u16.colors[v][k], want16[k]) << v;
  }
  EXPECT_EQ(scene::analyze(s).vertex_colored_meshes, 3u);
}

TEST(GltfFeatures, TextureSetsTransformsAndFilters) {
  const scene::Scene s = bundled("texture_transform.gltf");  // requires KHR_texture_transform
  ASSERT_EQ(s.materials.size(), 4u);
  const scene::TextureSlot& uv1 = s.materials[0].base_color_texture;
  EXPECT_EQ(uv1.texcoord, 1);
  EXPECT_TRUE(uv1.transform.identity());
  EXPECT_EQ(uv1.mag_filter, scene::Filter::Nearest);
  EXPECT_EQ(uv1.min_filter, scene::Filter::Nearest);
  EXPECT_EQ(uv1.mip_filter, scene::MipFilter::None);
  const scene::TextureSlot& offset = s.materials[1].base_color_texture;
  EXPECT_EQ(offset.texcoord, 0);
  EXPECT_FLOAT_EQ(offset.transform.apply({0.25f, 0.25f}).x, 0.75f);
  // Rotation pi/2, offset (0, 1): (u, v) -> (v, 1 - u).
  const glm::vec2 r = s.materials[2].base_color_texture.transform.apply({0.25f, 0.75f});
  EXPECT_NEAR(r.x, 0.75f, 1e-6f);
  EXPECT_NEAR(r.y, 0.75f, 1e-6f);
  const scene::TextureSlot& scaled = s.materials[3].base_color_texture;
  EXPECT_EQ(scaled.texcoord, 1);  // the extension's texCoord overrides the texture info's 0
  EXPECT_FLOAT_EQ(scaled.transform.area_scale(), 4.0f);
  // Panels 0 and 3 carry TEXCOORD_1; the others get zeros.
  EXPECT_EQ(s.meshes[0].uvs1.size(), s.meshes[0].positions.size());
  EXPECT_NE(s.meshes[0].uvs1[0], s.meshes[0].uvs[0]);
  const scene::SceneFeatures f = scene::analyze(s);
  EXPECT_EQ(f.second_uv_materials, 2u);
  EXPECT_EQ(f.texture_transform_materials, 3u);

  const scene::Scene filters = bundled("texture_filters.gltf");
  EXPECT_EQ(filters.materials[1].base_color_texture.mag_filter, scene::Filter::Linear);
  EXPECT_EQ(filters.materials[1].base_color_texture.mip_filter, scene::MipFilter::Linear);
  EXPECT_EQ(filters.materials[1].base_color_texture.wrap_s, scene::Wrap::ClampToEdge);
}

TEST(GltfFeatures, DielectricLayerExtensions) {
  const scene::Scene s = bundled("dielectric_panels.gltf");
  ASSERT_EQ(s.materials.size(), 4u);
  EXPECT_NEAR(s.materials[0].dielectric_f0().x, 0.04f, 1e-7f);
  EXPECT_NEAR(s.materials[1].dielectric_f0().x, 1.0f / 9.0f, 1e-7f);
  EXPECT_FLOAT_EQ(s.materials[2].specular, 0.5f);
  EXPECT_NEAR(s.materials[3].dielectric_f0().z, 0.01f, 1e-7f);
  EXPECT_EQ(scene::analyze(s).dielectric_materials, 3u);
  EXPECT_TRUE(s.warnings.empty());
}

// No TANGENT in the file: the generated frame's bitangent points up the image, world +Y here.
TEST(GltfFeatures, NormalMappedPanelsGetMikkTSpaceTangents) {
  const scene::Scene s = bundled("normal_map_plane.gltf");
  for (const scene::Mesh& m : s.meshes) {
    ASSERT_EQ(m.tangents.size(), m.positions.size());
    for (std::size_t v = 0; v < m.tangents.size(); ++v) {
      const glm::vec3 t(m.tangents[v]);
      const glm::vec3 b = glm::cross(m.normals[v], t) * m.tangents[v].w;
      EXPECT_NEAR(t.x, 1.0f, 1e-6f) << m.name << " " << v;
      EXPECT_NEAR(b.y, 1.0f, 1e-6f) << m.name << " " << v;
    }
  }
}

}  // namespace
