// Deringing windows: factor values, and that they reduce the ringing of a bright small light.
#include <cmath>

#include <gtest/gtest.h>

#include "sh/window.h"
#include "test_util.h"

namespace ddish::sh {
namespace {

TEST(ShWindow, Factors) {
  const BandScales hann = window_factors(Window::kHann, 3.0f);
  const float expect_hann[5] = {1.0f, 0.75f, 0.25f, 0.0f, 0.0f};
  const BandScales lanczos = window_factors(Window::kLanczos, 3.0f);
  const float expect_lanczos[5] = {1.0f, 0.8269933f, 0.4134967f, 0.0f, 0.0f};
  const BandScales none = window_factors(Window::kNone, 3.0f);
  for (std::size_t l = 0; l <= 4; ++l) {
    EXPECT_NEAR(hann[l], expect_hann[l], 1e-6f) << l;
    EXPECT_NEAR(lanczos[l], expect_lanczos[l], 1e-6f) << l;
    EXPECT_EQ(none[l], 1.0f);
  }
  // A wider window filters less.
  EXPECT_GT(window_factors(Window::kHann, 5.0f)[2], hann[2]);
}

// A small bright cap projected to L2 rings: the reconstruction goes negative on the far side.
// Windowing keeps the mean (band 0) and makes the negative dip shallower.
TEST(ShWindow, ReducesRingingOfSmallBrightLight) {
  const glm::vec3 axis = glm::normalize(glm::vec3(0.1f, 0.9f, 0.3f));
  double z[5];
  test::cap_factors(std::cos(0.2), z);
  const ShRgb sh = test::zonal_sh(z, axis, glm::vec3(1000.0f), 2);
  auto min_over_sphere = [](const ShRgb& s) {
    float m = 1e30f;
    for (int k = 0; k < 2000; ++k) m = std::min(m, eval(s, test::fibonacci_dir(k, 2000)).x);
    return m;
  };
  const float raw = min_over_sphere(sh);
  const float hann = min_over_sphere(apply_window(sh, Window::kHann, 3.0f));
  const float lanczos = min_over_sphere(apply_window(sh, Window::kLanczos, 3.0f));
  const float peak = eval(sh, axis).x;
  std::printf("[sh] L2 ringing of a small cap, min/peak: raw %.3f, Hann(3) %.3f, Lanczos(3) %.3f\n",
              raw / peak, hann / eval(apply_window(sh, Window::kHann, 3.0f), axis).x,
              lanczos / eval(apply_window(sh, Window::kLanczos, 3.0f), axis).x);
  EXPECT_LT(raw, 0.0f);
  EXPECT_GT(hann, 0.5f * raw);
  EXPECT_GT(lanczos, 0.7f * raw);
  EXPECT_EQ(apply_window(sh, Window::kHann, 3.0f)[0], sh[0]);
}

}  // namespace
}  // namespace ddish::sh
