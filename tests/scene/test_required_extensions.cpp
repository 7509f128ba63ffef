// Required extensions: a Draco file's accessors have no buffer view (the mesh data is in the
// extension's compressed buffer view), which tinygltf alone reports as an accessor error; ddish
// decodes Draco (scene/gltf_draco.h), and data that does not decode is one line naming the
// primitive and the extension, not tinygltf's accessor error.
#include <gtest/gtest.h>

#include <string>

#include "gltf_builder.h"
#include "scene/gltf_loader.h"
#include "scene/load_error.h"
#include "scene/required_extensions.h"

using namespace ddish;

namespace {

// A triangle laid out as a Draco encoder writes it: POSITION and indices accessors without
// buffer views, the primitive's KHR_draco_mesh_compression naming the compressed bytes, which
// are a Draco header followed by garbage.
test::GltfBuilder draco_triangle() {
  test::GltfBuilder b;
  const std::uint8_t compressed[12] = {'D', 'R', 'A', 'C', 'O', 2, 2, 1, 1, 0, 0, 0};
  const int view = b.add_view(compressed, sizeof compressed);
  b.doc["accessors"] = {{{"componentType", 5126}, {"count", 3}, {"type", "VEC3"},
                         {"min", {0, 0, 0}}, {"max", {1, 1, 0}}},
                        {{"componentType", 5123}, {"count", 3}, {"type", "SCALAR"}}};
  b.doc["meshes"] = {{{"primitives",
                       {{{"attributes", {{"POSITION", 0}}},
                         {"indices", 1},
                         {"extensions",
                          {{"KHR_draco_mesh_compression",
                            {{"bufferView", view}, {"attributes", {{"POSITION", 0}}}}}}}}}}}};
  b.add_node({{"mesh", 0}});
  b.doc["extensionsUsed"] = {"KHR_draco_mesh_compression"};
  b.doc["extensionsRequired"] = {"KHR_draco_mesh_compression"};
  return b;
}

}  // namespace

TEST(RequiredExtensions, CorruptDracoDataIsOneLineNamingThePrimitive) {
  for (test::BufferMode mode : {test::BufferMode::External, test::BufferMode::Glb}) {
    test::TempDir dir("draco");
    const std::string path = draco_triangle().write(
        dir.path.string(), mode == test::BufferMode::Glb ? "d.glb" : "d.gltf", mode);
    EXPECT_EQ(scene::required_extensions(path),
              std::vector<std::string>{"KHR_draco_mesh_compression"});
    const std::string msg = test::load_message(path);
    EXPECT_EQ(msg.rfind(path, 0), 0u) << msg;
    EXPECT_NE(msg.find("mesh 0 primitive 0: KHR_draco_mesh_compression (a required extension): "
                       "the Draco data cannot be decoded"),
              std::string::npos)
        << msg;
    EXPECT_EQ(msg.find("accessor"), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
}

TEST(RequiredExtensions, OptionalDracoWithoutFallbackDataIsAnErrorToo) {
  test::TempDir dir("draco_optional");
  test::GltfBuilder b = draco_triangle();
  b.doc.erase("extensionsRequired");
  const std::string msg = test::load_message(b.write(dir.path.string(), "o.gltf", test::BufferMode::External));
  EXPECT_NE(msg.find("primitive 0: KHR_draco_mesh_compression: the Draco data cannot be decoded"),
            std::string::npos)
      << msg;
}

// Optional Draco whose accessors also carry the uncompressed triangle: the corrupt Draco data is
// a warning and the plain data is used.
TEST(RequiredExtensions, OptionalDracoFallsBackToTheUncompressedData) {
  test::TempDir dir("draco_fallback");
  test::GltfBuilder b = draco_triangle();
  b.doc.erase("extensionsRequired");
  const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const std::uint16_t indices[4] = {0, 1, 2, 0};
  b.doc["accessors"][0]["bufferView"] = b.add_view(positions, sizeof positions);
  b.doc["accessors"][1]["bufferView"] = b.add_view(indices, sizeof indices);
  const scene::Scene s = scene::load_scene(b.write(dir.path.string(), "f.gltf", test::BufferMode::External));
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].positions.size(), 3u);
  EXPECT_EQ(s.meshes[0].positions[1], glm::vec3(1, 0, 0));
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("(optional) cannot be decoded, its uncompressed data is used"),
            std::string::npos)
      << s.warnings[0];
}

TEST(RequiredExtensions, NoneListedReadsEmpty) {
  test::TempDir dir("noreq");
  test::GltfBuilder b;
  b.add_node({{"mesh", b.add_quad_mesh()}});
  EXPECT_TRUE(scene::required_extensions(b.write(dir.path.string(), "q.gltf", test::BufferMode::External)).empty());
  EXPECT_TRUE(scene::required_extensions(dir.file("missing.gltf")).empty());
}
