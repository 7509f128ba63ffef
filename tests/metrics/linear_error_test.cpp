#include "metrics/linear_error.h"

#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

#include "metrics/errors.h"

namespace ddish::metrics {
namespace {

TEST(LinearError, RmseByHand) {
  // Black against (1, 2, 3) everywhere: squared errors 1, 4, 9 per pixel, mean 14/3.
  Image a(3, 2);
  Image b(3, 2, glm::vec3(1.0f, 2.0f, 3.0f));
  EXPECT_DOUBLE_EQ(rmse(a, b), std::sqrt(14.0 / 3.0));
  EXPECT_DOUBLE_EQ(rmse(b, b), 0.0);
}

TEST(LinearError, RmseOfOnePixel) {
  // One pixel of four off by (2, 0, 0): MSE = 4 / 12.
  Image a(2, 2), b(2, 2);
  a.at(0, 1) = {2.0f, 0.0f, 0.0f};
  EXPECT_DOUBLE_EQ(rmse(a, b), std::sqrt(4.0 / 12.0));
}

TEST(LinearError, RelativeMseByHand) {
  // Reference (1, 0, 2), image (0, 0, 3): terms 1/(1 + eps), 0, 1/(4 + eps), averaged over 3.
  Image a(1, 1, glm::vec3(0.0f, 0.0f, 3.0f));
  Image b(1, 1, glm::vec3(1.0f, 0.0f, 2.0f));
  const double eps = kRelMseEpsilon;
  EXPECT_DOUBLE_EQ(relative_mse(a, b), (1.0 / (1.0 + eps) + 1.0 / (4.0 + eps)) / 3.0);
  // The reference is the second argument: swapping changes the denominators.
  EXPECT_DOUBLE_EQ(relative_mse(b, a), (1.0 / (0.0 + eps) + 1.0 / (9.0 + eps)) / 3.0);
}

TEST(LinearError, DifferentSizesThrow) {
  EXPECT_THROW(rmse(Image(2, 2), Image(3, 2)), std::invalid_argument);
  EXPECT_THROW(relative_mse(Image(2, 2), Image(2, 1)), std::invalid_argument);
  EXPECT_THROW(compute_errors(Image(8, 8), Image(8, 9)), std::invalid_argument);
}

TEST(Errors, AllFiguresTogether) {
  Image a(12, 12, glm::vec3(0.25f));
  ImageErrors same = compute_errors(a, a);
  EXPECT_TRUE(std::isinf(same.psnr));
  EXPECT_NEAR(same.ssim, 1.0, 1e-12);
  EXPECT_EQ(same.rmse, 0.0);
  EXPECT_EQ(same.relmse, 0.0);

  Image b(12, 12, glm::vec3(0.5f));
  ImageErrors e = compute_errors(a, b);
  EXPECT_NEAR(e.rmse, 0.25, 1e-12);
  EXPECT_NEAR(e.relmse, 0.0625 / (0.25 + kRelMseEpsilon), 1e-12);
  EXPECT_GT(e.psnr, 0.0);
  EXPECT_LT(e.ssim, 1.0);
}

TEST(Errors, Formatting) {
  EXPECT_EQ(format_figure(std::numeric_limits<double>::infinity()), "inf");
  EXPECT_EQ(format_figure(-std::numeric_limits<double>::infinity()), "-inf");
  EXPECT_EQ(format_figure(std::nan("")), "nan");
  EXPECT_EQ(format_figure(6.020599913, 4), "6.021");
  ImageErrors e{std::numeric_limits<double>::infinity(), 1.0, 0.0, 0.0};
  nlohmann::ordered_json j = to_json(e);
  EXPECT_EQ(j["psnr"], "inf");
  EXPECT_EQ(j["ssim"], 1.0);
  EXPECT_EQ(j.dump(), R"({"psnr":"inf","ssim":1.0,"rmse":0.0,"relmse":0.0})");
}

}  // namespace
}  // namespace ddish::metrics
