// Shared by the multi-view command-line tests: run the built ddish binary (DDISH_EXE) in a
// per-test temporary folder, capture its output (cli_runner.h), and read the few facts of its
// files a test checks (PNG size from the header, the timings JSON).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "cli_runner.h"

namespace display_cli {

namespace fs = std::filesystem;

using cli::cornell;
using cli::quote;
using cli::Result;
using cli::slurp;

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

class Cli : public cli::TempDirTest {
 protected:
  Cli() : TempDirTest("ddish_display_cli_") {}
};

}  // namespace display_cli
