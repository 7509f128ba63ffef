#include "metrics/psnr.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include <gtest/gtest.h>

#include "test_util.h"

namespace ddish::metrics {
namespace {

using testing::grey_display;

TEST(Psnr, IdenticalImagesAreInfinite) {
  Image a(4, 3, glm::vec3(0.1f, 0.5f, 2.0f));
  EXPECT_EQ(psnr(a, a), std::numeric_limits<double>::infinity());
}

TEST(Psnr, OneChannelOfOnePixelFromBlackToWhite) {
  // 2x2 black against 2x2 black with one pixel's red channel at 1: of the 12 channel values one
  // differs by exactly 1, so MSE = 1/12 and PSNR = 10 log10(12).
  Image a(2, 2);
  Image b(2, 2);
  b.at(1, 0) = {1.0f, 0.0f, 0.0f};
  EXPECT_DOUBLE_EQ(display_mse(a, b), 1.0 / 12.0);
  EXPECT_NEAR(psnr(a, b), 10.0 * std::log10(12.0), 1e-12);
}

TEST(Psnr, ConstantDisplayValues) {
  // Display 0.25 against 0.75 everywhere: MSE = 0.5^2 = 0.25, PSNR = 10 log10(4) = 6.0206 dB.
  // (Display values pass through sRGB decode and encode in float, hence the small tolerance.)
  EXPECT_NEAR(psnr(grey_display(3, 5, 0.25f), grey_display(3, 5, 0.75f)), 10.0 * std::log10(4.0),
              1e-5);
}

TEST(Psnr, MeasuredOnClampedDisplayValues) {
  // Linear 4 and linear 1 both display as 1: no error on a display metric.
  EXPECT_EQ(psnr(Image(2, 2, glm::vec3(4.0f)), Image(2, 2, glm::vec3(1.0f))),
            std::numeric_limits<double>::infinity());
  // Negative linear values display as 0.
  EXPECT_EQ(display_mse(Image(2, 2, glm::vec3(-1.0f)), Image(2, 2)), 0.0);
}

TEST(Psnr, DifferentSizesThrow) {
  EXPECT_THROW(psnr(Image(2, 2), Image(2, 3)), std::invalid_argument);
  try {
    psnr(Image(64, 32), Image(64, 64));
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("64x32"), std::string::npos);
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
  }
}

}  // namespace
}  // namespace ddish::metrics
