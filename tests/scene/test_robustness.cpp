// Damaged files: every truncation and many byte flips of a small .glb and .gltf either load or
// throw a scene::LoadError; nothing else escapes and nothing crashes.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <random>

#include "gltf_builder.h"
#include "scene/gltf_loader.h"

using namespace ddish;

namespace {

std::string read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Loads `path`; returns 1 for a LoadError, 0 for success, and fails on anything else.
int outcome(const std::string& path) {
  try {
    scene::load_scene(path);
    return 0;
  } catch (const scene::LoadError&) {
    return 1;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not a LoadError: " << e.what();
  }
  return -1;
}

test::GltfBuilder small_scene() {
  test::GltfBuilder b;
  int mesh = b.add_quad_mesh();
  b.add_node({{"mesh", mesh}, {"children", {1}}});
  b.add_node({{"mesh", mesh}, {"translation", {0, 1, 0}}});
  b.doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorFactor", {1, 0, 0, 1}}}}}};
  return b;
}

}  // namespace

TEST(Robustness, EveryTruncationOfAGlb) {
  test::TempDir dir("trunc_glb");
  std::string good = small_scene().write(dir.path.string(), "s.glb", test::BufferMode::Glb);
  std::string bytes = read_all(good);
  std::string path = dir.file("cut.glb");
  int errors = 0;
  for (std::size_t n = 0; n < bytes.size(); n += 3) {
    test::write_file(path, bytes.substr(0, n));
    errors += outcome(path);
  }
  EXPECT_GT(errors, 0);
}

TEST(Robustness, ByteFlips) {
  std::mt19937 rng(1234);
  for (test::BufferMode mode : {test::BufferMode::Glb, test::BufferMode::DataUri}) {
    test::TempDir dir("flip");
    std::string good = small_scene().write(
        dir.path.string(), mode == test::BufferMode::Glb ? "s.glb" : "s.gltf", mode);
    std::string bytes = read_all(good);
    std::string path = dir.file(mode == test::BufferMode::Glb ? "f.glb" : "f.gltf");
    std::uniform_int_distribution<std::size_t> pos(0, bytes.size() - 1);
    std::uniform_int_distribution<int> val(0, 255);
    for (int i = 0; i < 200; ++i) {
      std::string damaged = bytes;
      for (int k = 0; k < 3; ++k) damaged[pos(rng)] = char(val(rng));
      test::write_file(path, damaged);
      outcome(path);
    }
  }
}
