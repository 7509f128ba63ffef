#include "metrics/image_io.h"

#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include <gtest/gtest.h>

#include "metrics/color.h"
#include "test_util.h"

namespace ddish::metrics {
namespace {

Image test_pattern() {
  Image img(5, 3);
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x)
      img.at(x, y) = {0.1f * float(x) + 0.01f, float(y) * 3.7f, -0.5f + 1e-6f * float(x * y)};
  return img;
}

TEST(Image, SizeAccessAndCrop) {
  Image img = test_pattern();
  EXPECT_EQ(img.width(), 5);
  EXPECT_EQ(img.height(), 3);
  EXPECT_EQ(img.pixel_count(), 15u);
  // Row-major, row 0 first.
  EXPECT_EQ(&img.pixels()[7], &img.at(2, 1));
  Image c = img.crop(1, 1, 3, 2);
  EXPECT_EQ(c.width(), 3);
  EXPECT_EQ(c.at(0, 0), img.at(1, 1));
  EXPECT_EQ(c.at(2, 1), img.at(3, 2));
  EXPECT_THROW(img.crop(3, 0, 3, 1), std::out_of_range);
  EXPECT_THROW(Image(-1, 2), std::invalid_argument);
}

TEST(Image, CountsNonFinitePixels) {
  Image img(3, 1);
  img.at(0, 0).y = std::numeric_limits<float>::quiet_NaN();
  img.at(2, 0).z = std::numeric_limits<float>::infinity();
  EXPECT_EQ(img.count_nonfinite(), 2u);
}

TEST(Color, SrgbRoundTripAndKnownValues) {
  EXPECT_FLOAT_EQ(srgb_encode(0.0f), 0.0f);
  EXPECT_FLOAT_EQ(srgb_encode(1.0f), 1.0f);
  EXPECT_NEAR(srgb_encode(0.18f), 0.4614f, 1e-4);  // middle grey
  for (float v : {0.001f, 0.0031308f, 0.05f, 0.5f, 0.9f})
    EXPECT_NEAR(srgb_decode(srgb_encode(v)), v, 1e-6f * std::max(1.0f, v * 10.0f));
  EXPECT_EQ(display_value(glm::vec3(-2.0f, 7.0f, 1.0f)), glm::vec3(0.0f, 1.0f, 1.0f));
  EXPECT_TRUE(std::isnan(display_value(glm::vec3(std::nanf(""))).x));
  EXPECT_FLOAT_EQ(luminance(glm::vec3(1.0f)), 1.0f);
}

TEST(ImageIo, ExrRoundTripIsExact) {
  auto dir = testing::scratch_dir();
  Image img = test_pattern();
  img.at(4, 2) = {1e-30f, 65504.0f * 4.0f, std::numeric_limits<float>::infinity()};
  write_image(dir / "a.exr", img);
  Image back = read_image(dir / "a.exr");
  ASSERT_EQ(back.width(), img.width());
  ASSERT_EQ(back.height(), img.height());
  for (std::size_t i = 0; i < img.pixel_count(); ++i)
    EXPECT_EQ(back.pixels()[i], img.pixels()[i]) << "pixel " << i;  // 32-bit float: bit exact
}

// The rasterizer's EXRs: values that are halves already (its RGBA16F pixels) come back exactly,
// including the extremes and the zeros of an atlas. (Sizes and times are measurements, in
// image_io.cpp, not pass marks.)
TEST(ImageIo, HalfExrKeepsHalfValuesExactly) {
  auto dir = testing::scratch_dir();
  Image img(7, 5);
  // Halves by construction: the extremes, and multiples of 3/8 below 2^11 (11 significant bits)
  // scaled by powers of two.
  const float extremes[] = {0.0f, 65504.0f, 0x1p-14f /* smallest normal */,
                            0x1p-24f /* smallest subnormal */, -2.5f,
                            std::numeric_limits<float>::infinity(), 1.5f};
  for (std::size_t i = 0; i < img.pixel_count(); ++i) {
    const float v = float(i) * 0.375f;
    img.pixels()[i] = i < 7 ? glm::vec3(extremes[i], -extremes[i], extremes[i])
                            : glm::vec3(v, -v, v * 0x1p-10f);
  }
  const auto row = [&](int y, float* rgb) {
    std::memcpy(rgb, &img.pixels()[std::size_t(y) * 7].x, 3 * 7 * sizeof(float));
  };
  write_exr_rows(dir / "half.exr", 7, 5, row, ExrPixels::half);
  const Image back = read_image(dir / "half.exr");
  for (std::size_t i = 0; i < img.pixel_count(); ++i)
    EXPECT_EQ(back.pixels()[i], img.pixels()[i]) << "pixel " << i;
}

TEST(ImageIo, PngHoldsDisplayValues) {
  auto dir = testing::scratch_dir();
  Image img = test_pattern();
  write_png(dir / "a.png", img);
  Image back = read_image(dir / "a.png");
  ASSERT_EQ(back.width(), img.width());
  ASSERT_EQ(back.height(), img.height());
  for (std::size_t i = 0; i < img.pixel_count(); ++i) {
    // 8 bits per channel: display values agree within half a step once read back and
    // re-encoded (out-of-range linear values were clamped on writing).
    glm::vec3 want = display_value(img.pixels()[i]);
    glm::vec3 got = display_value(back.pixels()[i]);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], 0.5f / 255.0f + 1e-6f);
  }
  // Top row first: row 0 is where the small values are.
  EXPECT_LT(back.at(0, 0).y, back.at(0, 2).y);
}

TEST(ImageIo, ErrorsAreOneLine) {
  auto dir = testing::scratch_dir();
  try {
    read_image(dir / "missing.exr");
    FAIL();
  } catch (const std::runtime_error& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find("missing.exr"), std::string::npos);
    EXPECT_EQ(msg.find('\n'), std::string::npos);
  }
  EXPECT_THROW(write_image(dir / "a.bmpx", Image(1, 1)), std::invalid_argument);
  EXPECT_THROW(write_exr(dir / "empty.exr", Image()), std::invalid_argument);
}

}  // namespace
}  // namespace ddish::metrics
