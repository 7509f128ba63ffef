// The ddish command line on scenes: `ddish info` succeeds on a bundled scene, and bad input
// gets exit code 2 and one line `ddish: error: FILE: PROBLEM` on stderr.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "cli_runner.h"

namespace {

using cli::Result;

// `ddish ARGS` with its output captured in a folder of its own, removed afterwards.
Result ddish(const std::string& args) {
  auto dir = std::filesystem::temp_directory_path() / ("ddish_cli_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  Result r = cli::run_ddish(dir, args);
  std::filesystem::remove_all(dir);
  return r;
}

std::string scene_path(const char* name) {
  return std::string(DDISH_SOURCE_DIR) + "/scenes/" + name;
}

// Exactly one line, starting with the prefix main() gives every user error.
void expect_one_error_line(const Result& r, const std::string& must_contain) {
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err.rfind("ddish: error: ", 0), 0u) << r.err;
  ASSERT_FALSE(r.err.empty());
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;
  EXPECT_NE(r.err.find(must_contain), std::string::npos) << r.err;
}

}  // namespace

TEST(InfoCli, InfoOnTheCornellBox) {
  Result r = ddish("info '" + scene_path("cornell_box.gltf") + "'");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("triangles"), std::string::npos);
  EXPECT_NE(r.out.find("shadow maps: the scene has no punctual lights"), std::string::npos)
      << r.out;
}

TEST(InfoCli, InfoJson) {
  Result r = ddish("info --json '" + scene_path("cornell_spot.gltf") + "'");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("\"spot_lights\": 1"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"left_out\""), std::string::npos);
}

TEST(InfoCli, MissingFile) {
  expect_one_error_line(ddish("info /nonexistent/nowhere.gltf"),
                        "/nonexistent/nowhere.gltf: no such file");
}

TEST(InfoCli, BrokenGltfAndSidecar) {
  auto dir =
      std::filesystem::temp_directory_path() / ("ddish_cli_bad_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::string gltf = (dir / "broken.gltf").string();
  std::ofstream(gltf) << "{\"asset\": {\"version\": \"2.0\"}, \"nodes\": [";
  expect_one_error_line(ddish("info '" + gltf + "'"), gltf);

  // A good scene with a broken sidecar beside it: the message names the sidecar.
  std::filesystem::copy_file(scene_path("cornell_box.gltf"), dir / "box.gltf");
  std::filesystem::copy_file(scene_path("cornell_box.bin"), dir / "cornell_box.bin");
  std::string sidecar = (dir / "box.ddish.json").string();
  std::ofstream(sidecar) << "{\"probe_grid\": {\"counts\": \"many\"}}";
  expect_one_error_line(ddish("info '" + (dir / "box.gltf").string() + "'"), sidecar);
  std::filesystem::remove_all(dir);
}

TEST(InfoCli, InfoNeedsAScene) {
  Result r = ddish("info");
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err.rfind("ddish: error: ", 0), 0u) << r.err;
}
