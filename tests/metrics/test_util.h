// Helpers shared by the metrics tests: images from display (sRGB-encoded) values, so a test can
// state expected PSNR and SSIM figures directly in display units, and per-test scratch folders.
#pragma once

#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <unistd.h>

#include "metrics/color.h"
#include "metrics/image.h"

namespace ddish::metrics::testing {

// A linear image whose display value is `display` (grey) everywhere.
inline Image grey_display(int w, int h, float display) {
  return Image(w, h, glm::vec3(srgb_decode(display)));
}

inline glm::vec3 grey_linear(float display) { return glm::vec3(srgb_decode(display)); }

// An empty scratch folder unique to the running test and process.
inline std::filesystem::path scratch_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::filesystem::path dir = std::filesystem::temp_directory_path() /
                              ("ddish_metrics_" + std::string(info->test_suite_name()) + "_" +
                               info->name() + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace ddish::metrics::testing
