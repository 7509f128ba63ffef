// glTF loading: buffer forms, hierarchy and transforms, materials, lights, cameras, textures.
#include <gtest/gtest.h>

#include <cmath>

#include "gltf_builder.h"
#include "scene/gltf_loader.h"

using namespace ddish;
using ddish::test::BufferMode;
using ddish::test::GltfBuilder;
using ddish::test::TempDir;

namespace {

void expect_vec3(const glm::vec3& v, float x, float y, float z, float eps = 1e-5f) {
  EXPECT_NEAR(v.x, x, eps);
  EXPECT_NEAR(v.y, y, eps);
  EXPECT_NEAR(v.z, z, eps);
}

// Root (translated by +10 x, rotated 90 degrees about Y) with a child scaled by 2 and
// translated by +1 y carrying the quad mesh, and the same mesh instanced at the root.
GltfBuilder hierarchy() {
  GltfBuilder b;
  int mesh = b.add_quad_mesh();
  float s = std::sqrt(0.5f);
  b.add_node({{"name", "root"},
              {"translation", {10, 0, 0}},
              {"rotation", {0, s, 0, s}},
              {"children", {1}},
              {"mesh", mesh}});
  b.add_node({{"name", "child"}, {"translation", {0, 1, 0}}, {"scale", {2, 2, 2}}, {"mesh", mesh}});
  b.doc["scenes"] = {{{"nodes", {0}}}};
  b.doc["scene"] = 0;
  return b;
}

}  // namespace

class BufferForms : public ::testing::TestWithParam<BufferMode> {};

TEST_P(BufferForms, HierarchyAndInstancing) {
  TempDir dir("loader");
  std::string path = hierarchy().write(
      dir.path.string(), GetParam() == BufferMode::Glb ? "h.glb" : "h.gltf", GetParam());
  scene::Scene s = scene::load_scene(path);
  ASSERT_EQ(s.meshes.size(), 1u);
  ASSERT_EQ(s.instances.size(), 2u);
  EXPECT_EQ(s.triangle_count(), 4u);
  EXPECT_EQ(s.nodes[1].parent, 0);
  // Child vertex (1,0,0): scale 2 -> (2,0,0), +1 y -> (2,1,0), rotate 90 deg about Y -> (0,1,-2),
  // then +10 x -> (10,1,-2).
  const scene::Instance& child = s.instances[1];
  EXPECT_EQ(child.node, 1);
  expect_vec3(glm::vec3(child.transform * glm::vec4(1, 0, 0, 1)), 10, 1, -2);
  expect_vec3(s.bounds().min, 10, 0, -2);
  expect_vec3(s.bounds().max, 10, 3, 0);
}

INSTANTIATE_TEST_SUITE_P(Loader, BufferForms,
                         ::testing::Values(BufferMode::External, BufferMode::DataUri,
                                           BufferMode::Glb));

TEST(Loader, NodeMatrixIsDecomposedToTrs) {
  TempDir dir("matrix");
  GltfBuilder b;
  int mesh = b.add_quad_mesh();
  // Column-major: rotate 90 deg about Z, scale 3, translate (1,2,3).
  b.add_node({{"mesh", mesh}, {"matrix", {0, 3, 0, 0, -3, 0, 0, 0, 0, 0, 3, 0, 1, 2, 3, 1}}});
  scene::Scene s = scene::load_scene(b.write(dir.path.string(), "m.gltf", BufferMode::External));
  expect_vec3(s.nodes[0].scale, 3, 3, 3);
  expect_vec3(s.nodes[0].translation, 1, 2, 3);
  expect_vec3(glm::vec3(s.instances[0].transform * glm::vec4(1, 0, 0, 1)), 1, 5, 3);
}

TEST(Loader, NonIndexedPrimitiveGetsIndicesNormalsAndTangents) {
  TempDir dir("nonindexed");
  GltfBuilder b;
  b.add_node({{"mesh", b.add_quad_mesh(false)}});
  scene::Scene s = scene::load_scene(b.write(dir.path.string(), "n.gltf", BufferMode::DataUri));
  const scene::Mesh& m = s.meshes[0];
  ASSERT_EQ(m.indices.size(), 6u);
  EXPECT_EQ(m.indices[5], 5u);
  ASSERT_EQ(m.normals.size(), 6u);
  ASSERT_EQ(m.tangents.size(), 6u);
  expect_vec3(m.normals[0], 0, 0, 1);
  // u grows along +x, v (glTF: down the image) grows along -y: tangent +x, and MikkTSpace's
  // bitangent points up the image (-v, the normal map's +Y), +y = cross(N, T): w = +1.
  expect_vec3(glm::vec3(m.tangents[0]), 1, 0, 0);
  EXPECT_EQ(m.tangents[0].w, 1.0f);
}

TEST(Loader, MaterialsLightsCamerasAndTextures) {
  TempDir dir("materials");
  GltfBuilder b;
  // A 2x1 PNG written by hand would need zlib; a 2x1 binary PPM is not glTF, so use a tiny
  // uncompressed BMP, which stb_image decodes (the loader accepts what stb_image accepts).
  std::vector<std::uint8_t> bmp = {
      'B', 'M', 62, 0, 0, 0, 0, 0,  0, 0, 54, 0, 0, 0, 40,  0, 0,   0, 2, 0, 0,
      0,   1,   0,  0, 0, 1, 0, 24, 0, 0, 0,  0, 0, 8, 0,   0, 0,   0, 0, 0, 0,
      0,   0,   0,  0, 0, 0, 0, 0,  0, 0, 0,  0, 0, 0, 255, 0, 255, 0, 0, 0};  // pixels BGR: red,
                                                                               // green
  test::write_file(dir.file("tex.bmp"), std::string(bmp.begin(), bmp.end()));
  b.doc["images"] = {{{"uri", "tex.bmp"}}};
  b.doc["samplers"] = {{{"wrapS", 33071}, {"wrapT", 33648}}};  // clamp, mirrored repeat
  b.doc["textures"] = {{{"source", 0}, {"sampler", 0}}};
  b.doc["materials"] = {
      {{"name", "glow"},
       {"pbrMetallicRoughness",
        {{"baseColorFactor", {0.5, 0.25, 1, 1}},
         {"metallicFactor", 0.0},
         {"roughnessFactor", 0.3},
         {"baseColorTexture", {{"index", 0}}}}},
       {"normalTexture", {{"index", 0}, {"scale", 0.5}}},
       {"emissiveFactor", {1, 0.5, 0}},
       {"alphaMode", "MASK"},
       {"alphaCutoff", 0.25},
       {"doubleSided", true},
       {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 12}}}}}}};
  b.doc["extensionsUsed"] = {"KHR_lights_punctual", "KHR_materials_emissive_strength",
                             "KHR_materials_sheen"};
  b.doc["extensions"]["KHR_lights_punctual"]["lights"] = {
      {{"type", "spot"},
       {"name", "spot"},
       {"intensity", 40},
       {"color", {1, 0.9, 0.8}},
       {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.6}}}}};
  b.doc["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.7}, {"znear", 0.05}}}}};
  int mesh = b.add_quad_mesh(true, 0);
  // Light pointing down: rotate -90 deg about X turns -Z into -Y.
  float s = std::sqrt(0.5f);
  b.add_node({{"mesh", mesh}});
  b.add_node({{"name", "lamp"},
              {"translation", {0, 2, 0}},
              {"rotation", {-s, 0, 0, s}},
              {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  b.add_node({{"name", "Cam"}, {"translation", {0, 1, 5}}, {"camera", 0}});
  std::string path = b.write(dir.path.string(), "mat.gltf", BufferMode::External);

  scene::Scene sc = scene::load_scene(path);
  ASSERT_EQ(sc.materials.size(), 1u);
  const scene::Material& m = sc.materials[0];
  EXPECT_FLOAT_EQ(m.base_color.g, 0.25f);
  EXPECT_FLOAT_EQ(m.metallic, 0.0f);
  EXPECT_FLOAT_EQ(m.roughness, 0.3f);
  EXPECT_FLOAT_EQ(m.normal_scale, 0.5f);
  EXPECT_EQ(m.alpha_mode, scene::AlphaMode::Mask);
  EXPECT_FLOAT_EQ(m.alpha_cutoff, 0.25f);
  EXPECT_TRUE(m.double_sided);
  expect_vec3(m.emission(), 12, 6, 0);
  EXPECT_EQ(m.base_color_texture.texture, 0);
  EXPECT_EQ(m.normal_texture.texture, 0);
  EXPECT_FALSE(m.emissive_texture);
  EXPECT_EQ(m.base_color_texture.wrap_s, scene::Wrap::ClampToEdge);
  EXPECT_EQ(m.base_color_texture.wrap_t, scene::Wrap::MirroredRepeat);
  ASSERT_EQ(sc.warnings.size(), 1u);  // the optional extension ddish ignores
  EXPECT_NE(sc.warnings[0].find("KHR_materials_sheen"), std::string::npos);
  ASSERT_EQ(sc.textures.size(), 1u);
  ASSERT_EQ(sc.textures[0].width, 2);
  ASSERT_EQ(sc.textures[0].rgba8.size(), 8u);
  EXPECT_EQ(sc.textures[0].rgba8[0], 255);  // red
  EXPECT_EQ(sc.textures[0].rgba8[5], 255);  // green
  EXPECT_EQ(sc.textures[0].rgba8[3], 255);  // opaque

  ASSERT_EQ(sc.lights.size(), 1u);
  const scene::Light& l = sc.lights[0];
  EXPECT_EQ(l.type, scene::LightType::Spot);
  EXPECT_FLOAT_EQ(l.intensity, 40.0f / scene::kLumensPerWatt);  // 40 cd: no sidecar, glTF units
  EXPECT_FLOAT_EQ(l.outer_cone, 0.6f);
  expect_vec3(l.position, 0, 2, 0);
  expect_vec3(l.direction, 0, -1, 0);

  ASSERT_EQ(sc.cameras.size(), 1u);
  EXPECT_EQ(sc.cameras[0].name, "Cam");
  expect_vec3(sc.cameras[0].eye, 0, 1, 5);
  expect_vec3(sc.cameras[0].forward, 0, 0, -1);
  expect_vec3(sc.cameras[0].up, 0, 1, 0);
  EXPECT_EQ(sc.default_camera(), &sc.cameras[0]);

  // Header-only mode: sizes, no pixels.
  scene::LoadOptions opt;
  opt.decode_textures = false;
  scene::Scene quick = scene::load_scene(path, opt);
  EXPECT_EQ(quick.textures[0].width, 2);
  EXPECT_EQ(quick.textures[0].height, 1);
  EXPECT_TRUE(quick.textures[0].rgba8.empty());
}

TEST(Loader, SidecarBesideTheFileIsRead) {
  TempDir dir("sidecar");
  GltfBuilder b;
  b.add_node({{"mesh", b.add_quad_mesh()}});
  b.doc["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.7}, {"znear", 0.05}}}}};
  b.add_node({{"name", "A"}, {"camera", 0}});
  b.add_node({{"name", "B"}, {"camera", 0}});
  std::string path = b.write(dir.path.string(), "room.gltf", BufferMode::External);
  EXPECT_EQ(scene::load_scene(path).default_camera()->name, "A");
  test::write_file(dir.file("room.ddish.json"),
                   R"({"environment": {"radiance": [0.5, 0.25, 1]}, "camera": "B",
                       "probe_grid": {"counts": [4, 2, 3], "bounds": {"min": [0,0,0], "max": [1,2,3]}}})");
  scene::Scene s = scene::load_scene(path);
  EXPECT_EQ(s.default_camera()->name, "B");
  expect_vec3(s.environment(), 0.5f, 0.25f, 1.0f);
  ASSERT_TRUE(s.sidecar.probe_counts.has_value());
  EXPECT_EQ(s.sidecar.probe_counts->z, 3);
  ASSERT_TRUE(s.sidecar.probe_bounds.has_value());
  expect_vec3(s.sidecar.probe_bounds->max, 1, 2, 3);
}
