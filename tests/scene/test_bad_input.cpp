// Bad input: every problem becomes one scene::LoadError whose one-line message names the file
// and the problem; nothing crashes or aborts.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>

#include "gltf_builder.h"
#include "scene/gltf_loader.h"

using namespace ddish;
using ddish::test::BufferMode;
using ddish::test::GltfBuilder;
using ddish::test::TempDir;

namespace {

// Loads `path` expecting a LoadError; returns its message after checking the common shape.
std::string load_error(const std::string& path, const std::string& named_file = "") {
  try {
    scene::load_scene(path);
  } catch (const scene::LoadError& e) {
    std::string msg = e.what();
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    EXPECT_EQ(msg.rfind(named_file.empty() ? path : named_file, 0), 0u) << msg;
    return msg;
  }
  ADD_FAILURE() << "no LoadError for " << path;
  return {};
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

GltfBuilder one_quad() {
  GltfBuilder b;
  b.add_node({{"mesh", b.add_quad_mesh()}});
  return b;
}

}  // namespace

TEST(BadInput, MissingFile) {
  std::string msg = load_error("/nonexistent/dir/scene.gltf");
  EXPECT_TRUE(contains(msg, "no such file")) << msg;
}

TEST(BadInput, TruncatedGltf) {
  TempDir dir("trunc");
  std::string path = one_quad().write(dir.path.string(), "t.gltf", BufferMode::DataUri);
  std::ifstream in(path);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  test::write_file(path, text.substr(0, text.size() / 2));
  load_error(path);
}

TEST(BadInput, TruncatedGlb) {
  TempDir dir("truncglb");
  std::string path = one_quad().write(dir.path.string(), "t.glb", BufferMode::Glb);
  std::filesystem::resize_file(path, std::filesystem::file_size(path) - 40);
  load_error(path);
  std::filesystem::resize_file(path, 14);  // shorter than a GLB header
  load_error(path);
}

TEST(BadInput, NotJsonAtAll) {
  TempDir dir("garbage");
  test::write_file(dir.file("g.gltf"), "this is not a glTF file");
  load_error(dir.file("g.gltf"));
}

TEST(BadInput, MissingExternalBuffer) {
  TempDir dir("nobuf");
  std::string path = one_quad().write(dir.path.string(), "b.gltf", BufferMode::External);
  std::filesystem::remove(path + ".bin");
  load_error(path);
}

TEST(BadInput, AccessorOutOfRange) {
  TempDir dir("accessor");
  GltfBuilder b = one_quad();
  b.doc["accessors"][0]["count"] = 400;  // POSITION reads past its buffer view
  std::string msg = load_error(b.write(dir.path.string(), "a.gltf", BufferMode::External));
  EXPECT_TRUE(contains(msg, "out of range")) << msg;
  EXPECT_TRUE(contains(msg, "POSITION")) << msg;
}

TEST(BadInput, HugeAccessorCountIsRejectedBeforeAllocating) {
  TempDir dir("huge");
  GltfBuilder b = one_quad();
  b.doc["accessors"][1].erase("bufferView");  // all zeros: nothing bounds the count
  b.doc["accessors"][1]["count"] = std::uint64_t(1) << 40;
  std::string msg = load_error(b.write(dir.path.string(), "h.gltf", BufferMode::External));
  EXPECT_TRUE(contains(msg, "out of range")) << msg;
  b.doc["accessors"][1]["bufferView"] = 0;  // backed by 48 bytes
  msg = load_error(b.write(dir.path.string(), "h.gltf", BufferMode::External));
  EXPECT_TRUE(contains(msg, "out of range")) << msg;
}

TEST(BadInput, AccessorOffsetPastBufferView) {
  TempDir dir("offset");
  GltfBuilder b = one_quad();
  b.doc["accessors"][1]["byteOffset"] = std::numeric_limits<std::uint32_t>::max();
  std::string msg = load_error(b.write(dir.path.string(), "o.gltf", BufferMode::External));
  EXPECT_TRUE(contains(msg, "TEXCOORD_0")) << msg;
}

TEST(BadInput, IndexOutOfRange) {
  TempDir dir("index");
  GltfBuilder b;
  std::vector<float> pos = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  nlohmann::json prim = {{"attributes", {{"POSITION", b.add_floats(pos, "VEC3", 3)}}},
                         {"indices", b.add_indices({0, 1, 7})}};
  b.doc["meshes"] = {{{"primitives", {prim}}}};
  b.add_node({{"mesh", 0}});
  std::string msg = load_error(b.write(dir.path.string(), "i.gltf", BufferMode::External));
  EXPECT_TRUE(contains(msg, "index 7")) << msg;
}

TEST(BadInput, NonFinitePositions) {
  for (float bad :
       {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    TempDir dir("nan");
    GltfBuilder b;
    std::vector<float> pos = {0, 0, 0, 1, 0, 0, 0, bad, 0};
    b.doc["meshes"] = {
        {{"primitives", {{{"attributes", {{"POSITION", b.add_floats(pos, "VEC3", 3)}}}}}}}};
    b.add_node({{"mesh", 0}});
    std::string msg = load_error(b.write(dir.path.string(), "n.gltf", BufferMode::External));
    EXPECT_TRUE(contains(msg, "vertex 2 is not finite")) << msg;
  }
}

TEST(BadInput, UndecodableTexture) {
  TempDir dir("texture");
  GltfBuilder b = one_quad();
  test::write_file(dir.file("broken.png"), "\x89PNG\r\n\x1a\n but then nothing an image holds");
  b.doc["images"] = {{{"uri", "broken.png"}}};
  b.doc["textures"] = {{{"source", 0}}};
  std::string path = b.write(dir.path.string(), "t.gltf", BufferMode::External);
  std::string msg = load_error(path);
  EXPECT_TRUE(contains(msg, "broken.png")) << msg;
  // Reading headers only (ddish info) still notices that this is no image.
  scene::LoadOptions headers_only;
  headers_only.decode_textures = false;
  EXPECT_THROW(scene::load_scene(path, headers_only), scene::LoadError);
}

TEST(BadInput, MissingTextureFile) {
  TempDir dir("notexture");
  GltfBuilder b = one_quad();
  b.doc["images"] = {{{"uri", "absent.png"}}};
  std::string msg = load_error(b.write(dir.path.string(), "t.gltf", BufferMode::External));
  EXPECT_TRUE(contains(msg, "absent.png")) << msg;
}

TEST(BadInput, UnknownRequiredExtension) {
  TempDir dir("ext");
  GltfBuilder b = one_quad();
  b.doc["extensionsUsed"] = {"EXT_meshopt_compression"};
  b.doc["extensionsRequired"] = {"EXT_meshopt_compression"};
  std::string msg = load_error(b.write(dir.path.string(), "e.gltf", BufferMode::External));
  EXPECT_TRUE(contains(msg, "requires unsupported extension EXT_meshopt_compression")) << msg;
}

TEST(BadInput, BrokenSidecar) {
  TempDir dir("sidecar");
  std::string path = one_quad().write(dir.path.string(), "s.gltf", BufferMode::External);
  std::string sidecar = dir.file("s.ddish.json");
  test::write_file(sidecar, R"({"environment": {"radiance": [1, 2)");
  std::string msg = load_error(path, sidecar);
  EXPECT_TRUE(contains(msg, "not valid JSON")) << msg;
  test::write_file(sidecar, R"({"probe_grid": {"counts": [4, 0, 4]}})");
  msg = load_error(path, sidecar);
  EXPECT_TRUE(contains(msg, "probe_grid.counts")) << msg;
  test::write_file(sidecar, R"({"camera": "Nowhere"})");
  msg = load_error(path, sidecar);
  EXPECT_TRUE(contains(msg, "Nowhere")) << msg;
}

TEST(BadInput, NodeHierarchyWithCycle) {
  TempDir dir("cycle");
  GltfBuilder b = one_quad();
  b.add_node({{"children", {2}}});
  b.add_node({{"children", {1}}});
  std::string msg = load_error(b.write(dir.path.string(), "c.gltf", BufferMode::External));
  EXPECT_TRUE(contains(msg, "cycle")) << msg;
}

TEST(BadInput, MaterialIndexOutOfRange) {
  TempDir dir("material");
  GltfBuilder b = one_quad();
  b.doc["meshes"][0]["primitives"][0]["material"] = 3;
  std::string msg = load_error(b.write(dir.path.string(), "m.gltf", BufferMode::External));
  EXPECT_TRUE(contains(msg, "material 3")) << msg;
}

TEST(BadInput, ImageBufferViewPastItsBuffer) {
  TempDir dir("imageview");
  GltfBuilder b = one_quad();
  b.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 4}, {"byteLength", 1 << 20}});
  b.doc["images"] = {
      {{"bufferView", int(b.doc["bufferViews"].size()) - 1}, {"mimeType", "image/png"}}};
  load_error(b.write(dir.path.string(), "v.glb", BufferMode::Glb));
}
