// Shared by the command-line tests: run the built ddish binary (DDISH_EXE) with its stdout and
// stderr captured in files of a folder, and a fixture giving every test its own temporary folder.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>

#include <gtest/gtest.h>

namespace cli {

namespace fs = std::filesystem;

struct Result {
  int code = -1;
  std::string out;
  std::string err;
};

// 'text' for the shell, appended piece by piece: GCC 12 at -O3 warns (-Wrestrict, a known false
// positive) on "'" + std::string + "'" chains.
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

// The bundled Cornell box, quoted for the shell.
inline std::string cornell() {
  return quote(std::string(DDISH_SOURCE_DIR) + "/scenes/cornell_box.gltf");
}

// `ddish ARGS` with an optional environment prefix ("DDISH_VALIDATION=1"), its stdout and
// stderr written to `dir`/stdout and `dir`/stderr (the folder must exist) and read back.
inline Result run_ddish(const fs::path& dir, const std::string& args, const std::string& env = "") {
  std::string cmd = env.empty() ? "" : env + " ";
  cmd += quote(DDISH_EXE);
  cmd += ' ';
  cmd += args;
  cmd += " >";
  cmd += quote((dir / "stdout").string());
  cmd += " 2>";
  cmd += quote((dir / "stderr").string());
  const int status = std::system(cmd.c_str());
  Result r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(dir / "stdout");
  r.err = slurp(dir / "stderr");
  return r;
}

// A fresh folder per test, PREFIX + test name + "_" + process id under the system temporary
// folder, removed after the test; run() captures ddish's output there.
class TempDirTest : public ::testing::Test {
 protected:
  explicit TempDirTest(std::string prefix) : prefix_(std::move(prefix)) {}

  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           (prefix_ + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  Result run(const std::string& args, const std::string& env = "") const {
    return run_ddish(dir_, args, env);
  }

  // A file in the test's folder, quoted for the shell.
  std::string path(const std::string& name) const { return quote((dir_ / name).string()); }

  fs::path dir_;

 private:
  std::string prefix_;
};

}  // namespace cli
