// A scene too large for memory is refused before the file is read or a texture decoded, with
// one line naming what it needs (scene/memory_check.h).
#include <gtest/gtest.h>

#include <fcntl.h>
#include <unistd.h>

#include <string>

#include "gltf_builder.h"
#include "scene/gltf_loader.h"
#include "scene/load_error.h"
#include "scene/memory_check.h"

using namespace ddish;
using ddish::test::BufferMode;
using ddish::test::GltfBuilder;
using ddish::test::TempDir;

namespace {

constexpr std::uint64_t kGiB = std::uint64_t{1} << 30;

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// A PNG signature and IHDR chunk only: 16384 x 16384 RGBA8, the largest image stb_image
// accepts (1 GiB decoded). Its header is all a size check reads; its pixels never come.
std::string huge_png_header() {
  const unsigned char bytes[] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n',  // signature
                                 0, 0, 0, 13, 'I', 'H', 'D', 'R',              // IHDR, 13 bytes
                                 0, 0, 0x40, 0, 0, 0, 0x40, 0,                 // 16384 x 16384
                                 8, 6, 0, 0, 0,                                // 8-bit RGBA
                                 0, 0, 0, 0};                                  // CRC (unchecked)
  return std::string(reinterpret_cast<const char*>(bytes), sizeof bytes);
}

}  // namespace

TEST(MemoryCheck, TextureBytesAreThePixelsPlusTheLargestWorkingCopy) {
  std::vector<scene::Texture> t(3);
  t[0].width = 1024, t[0].height = 512;   // 2 MiB
  t[1].width = 2048, t[1].height = 2048;  // 16 MiB, the largest
  t[2].width = 1, t[2].height = 1;        // 4 bytes
  EXPECT_EQ(scene::texture_decode_bytes(t), (2u << 20) + (16u << 20) + 4 + (16u << 20));
  EXPECT_EQ(scene::texture_decode_bytes({}), 0u);
}

TEST(MemoryCheck, AFileNeedsTwiceItsSize) {
  EXPECT_NO_THROW(scene::check_file_fits("f.glb", 10 * kGiB, 20 * kGiB));
  EXPECT_THROW(scene::check_file_fits("f.glb", 10 * kGiB, 20 * kGiB - 1), scene::LoadError);
  EXPECT_THROW(scene::check_file_fits("f.glb", UINT64_MAX - 1, UINT64_MAX - 2), scene::LoadError);
}

TEST(MemoryCheck, TexturesLargerThanMemoryAreRefusedBeforeDecoding) {
  // 1000 images of 1 GiB each: 1001 GiB to decode, more than any machine this suite runs on.
  TempDir dir("hugetextures");
  test::write_file(dir.file("huge.png"), huge_png_header());
  GltfBuilder b;
  std::vector<float> pos = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  b.doc["meshes"] = {{{"primitives", {{{"attributes", {{"POSITION", b.add_floats(pos, "VEC3", 3)}}}}}}}};
  b.add_node({{"mesh", 0}});
  for (int i = 0; i < 1000; ++i) b.doc["images"].push_back({{"uri", "huge.png"}});
  const std::string path = b.write(dir.path.string(), "t.gltf", BufferMode::External);
  const std::string msg = test::load_message(path);
  EXPECT_TRUE(contains(msg, "its 1000 images decode to 1001.0 GiB")) << msg;
  EXPECT_TRUE(contains(msg, "16384x16384")) << msg;
  EXPECT_TRUE(contains(msg, "of memory available")) << msg;
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  // Reading sizes only (ddish info) decodes nothing, so it still loads.
  scene::LoadOptions headers_only;
  headers_only.decode_textures = false;
  EXPECT_EQ(scene::load_scene(path, headers_only).textures.size(), 1000u);
}

TEST(MemoryCheck, AFileLargerThanMemoryIsRefusedBeforeReading) {
  // A sparse 4 TiB .glb: its size is known at once, and not a byte of it is read.
  TempDir dir("hugefile");
  const std::string path = dir.file("huge.glb");
  test::write_file(path, "glTF");
  const int fd = ::open(path.c_str(), O_WRONLY);
  ASSERT_GE(fd, 0);
  const bool sparse = ::ftruncate(fd, off_t(4096) * off_t(kGiB)) == 0;
  ::close(fd);
  if (!sparse) GTEST_SKIP() << "the temp folder's file system has no 4 TiB sparse files";
  const std::string msg = test::load_message(path);
  EXPECT_TRUE(contains(msg, "the file is 4096.0 GiB and reading it needs 8192.0 GiB")) << msg;
}
