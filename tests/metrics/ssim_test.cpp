#include "metrics/ssim.h"

#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

#include "test_util.h"

namespace ddish::metrics {
namespace {

using testing::grey_display;
using testing::grey_linear;

constexpr double kC1 = 0.01 * 0.01;  // (K1 L)^2
constexpr double kC2 = 0.03 * 0.03;  // (K2 L)^2

TEST(Ssim, ImageWithItselfIsOne) {
  Image a(23, 17);
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x)
      a.at(x, y) = {0.03f * float(x), 0.05f * float(y), 0.5f * float((x * y) % 3)};
  EXPECT_NEAR(ssim(a, a), 1.0, 1e-12);
}

TEST(Ssim, ConstantImagesFollowTheLuminanceTerm) {
  // Constant images have zero variance and covariance, so every window gives
  // (2 mu_a mu_b + C1) / (mu_a^2 + mu_b^2 + C1) * (0 + C2) / (0 + C2). Grey display values are
  // their own luminance (the Rec. 709 weights sum to 1).
  const double ma = 0.3, mb = 0.6;
  const double expected = (2 * ma * mb + kC1) / (ma * ma + mb * mb + kC1);
  EXPECT_NEAR(ssim(grey_display(16, 16, 0.3f), grey_display(16, 16, 0.6f)), expected, 1e-6);
  // Smaller than the window in both directions (a single, truncated window): the same figure.
  EXPECT_NEAR(ssim(grey_display(3, 2, 0.3f), grey_display(3, 2, 0.6f)), expected, 1e-6);
}

TEST(Ssim, TwoByTwoByHand) {
  // A 2x2 image has one window, the Gaussian's centre truncated to 2x2: four equal weights 1/4.
  // Display values a = (0.2, 0.4, 0.6, 0.8), b = (0.2, 0.4, 0.6, 1.0), row by row.
  Image a(2, 2), b(2, 2);
  a.at(0, 0) = grey_linear(0.2f), a.at(1, 0) = grey_linear(0.4f);
  a.at(0, 1) = grey_linear(0.6f), a.at(1, 1) = grey_linear(0.8f);
  b.at(0, 0) = grey_linear(0.2f), b.at(1, 0) = grey_linear(0.4f);
  b.at(0, 1) = grey_linear(0.6f), b.at(1, 1) = grey_linear(1.0f);
  // mu_a = 2.0/4 = 0.5, mu_b = 2.2/4 = 0.55
  // E[a^2] = (0.04 + 0.16 + 0.36 + 0.64)/4 = 0.30 -> var_a = 0.30 - 0.25 = 0.05
  // E[b^2] = (0.04 + 0.16 + 0.36 + 1.00)/4 = 0.39 -> var_b = 0.39 - 0.3025 = 0.0875
  // E[ab]  = (0.04 + 0.16 + 0.36 + 0.80)/4 = 0.34 -> cov   = 0.34 - 0.275 = 0.065
  const double mu_a = 0.5, mu_b = 0.55, var_a = 0.05, var_b = 0.0875, cov = 0.065;
  const double expected = (2 * mu_a * mu_b + kC1) * (2 * cov + kC2) /
                          ((mu_a * mu_a + mu_b * mu_b + kC1) * (var_a + var_b + kC2));
  EXPECT_NEAR(ssim(a, b), expected, 1e-6);
  EXPECT_NEAR(ssim(b, a), expected, 1e-6);  // symmetric
}

TEST(Ssim, UsesLuminanceOfDisplayValues) {
  // Pure green at display 1 against grey at display 0.7152: equal luminance, equal (zero)
  // variance, so SSIM cannot tell them apart.
  Image green(12, 12, glm::vec3(0.0f, 1.0f, 0.0f));
  Image grey = grey_display(12, 12, 0.7152f);
  EXPECT_NEAR(ssim(green, grey), 1.0, 1e-6);
}

TEST(Ssim, MeanOverValidWindowsOnly) {
  // 21x11: 11 valid window positions along x, one along y. A change in the last column is seen
  // only by the last window, so 10 of the 11 SSIM values stay 1 and the mean is above 10/11.
  Image a = grey_display(21, 11, 0.5f);
  Image b = a;
  for (int y = 0; y < 11; ++y) b.at(20, y) = grey_linear(y % 2 ? 1.0f : 0.0f);
  double s = ssim(a, b);
  EXPECT_LT(s, 1.0);
  EXPECT_GT(s, 10.0 / 11.0);
}

TEST(Ssim, NoiseLowersIt) {
  Image a = grey_display(32, 32, 0.5f);
  Image b = a;
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x)
      if ((x * 7 + y * 13) % 5 == 0) b.at(x, y) = grey_linear(0.9f);
  double s = ssim(a, b);
  EXPECT_GT(s, 0.0);
  EXPECT_LT(s, 0.5);
}

TEST(Ssim, DifferentSizesThrow) {
  EXPECT_THROW(ssim(Image(16, 16), Image(16, 15)), std::invalid_argument);
  EXPECT_THROW(ssim(Image(), Image()), std::invalid_argument);
}

}  // namespace
}  // namespace ddish::metrics
