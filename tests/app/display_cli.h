// Shared by the multi-view command-line tests: run the built ddish binary (DDISH_EXE) in a
// per-test temporary folder, capture its output, and read the few facts of its files a test
// checks (PNG size from the header, the timings JSON).
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace display_cli {

namespace fs = std::filesystem;

struct Result {
  int code = -1;
  std::string out;
  std::string err;
};

// 'text' for the shell, appended piece by piece (GCC 12 -Wrestrict false positive on chains).
inline std::string quote(const std::string& text) {
  std::string q;
  q += '\'';
  q += text;
  q += '\'';
  return q;
}

inline std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline std::string cornell() {
  return quote(std::string(DDISH_SOURCE_DIR) + "/scenes/cornell_box.gltf");
}

// Width and height from a PNG's IHDR chunk (bytes 16..23, big-endian); {0, 0} if not a PNG.
inline std::pair<int, int> png_size(const fs::path& p) {
  const std::string b = slurp(p);
  if (b.size() < 24 || b.compare(1, 3, "PNG") != 0) return {0, 0};
  auto be32 = [&](std::size_t at) {
    std::uint32_t v = 0;
    for (std::size_t i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(b[at + i]);
    return static_cast<int>(v);
  };
  return {be32(16), be32(20)};
}

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("ddish_display_cli_" + std::string(info->name()) + "_" +
                                        std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // `ddish ARGS` with an optional environment prefix ("DDISH_VALIDATION=1").
  Result run(const std::string& args, const std::string& env = "") const {
    std::string cmd = env.empty() ? "" : env + " ";
    cmd += quote(DDISH_EXE);
    cmd += ' ';
    cmd += args;
    cmd += " >";
    cmd += quote((dir_ / "stdout").string());
    cmd += " 2>";
    cmd += quote((dir_ / "stderr").string());
    const int status = std::system(cmd.c_str());
    Result r;
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = slurp(dir_ / "stdout");
    r.err = slurp(dir_ / "stderr");
    return r;
  }

  std::string path(const std::string& name) const { return quote((dir_ / name).string()); }

  fs::path dir_;
};

}  // namespace display_cli
