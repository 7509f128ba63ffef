#include "raster/half_rgb_pixels.h"

#include <vector>

#include <gtest/gtest.h>

namespace ddish::raster {
namespace {

// Values a RGBA16F target holds: zero, a subnormal, ordinary values, the largest half, negatives.
const std::vector<float> kHalves = {0.0f, 0x1p-24f, 0.5f, 1.0f, 3.140625f, 1000.0f, 65504.0f, -2.25f, 6.1035156e-05f};

HalfRgbPixels filled(const std::vector<glm::vec3>& rgb) {
  HalfRgbPixels p(rgb.size());
  for (std::size_t i = 0; i < rgb.size(); ++i)
    for (int c = 0; c < 3; ++c) p.halves()[3 * i + c] = sh::float_to_half(rgb[i][c]);
  return p;
}

std::vector<glm::vec3> sample_pixels() {
  std::vector<glm::vec3> rgb;
  for (std::size_t i = 0; i + 2 < kHalves.size(); ++i) rgb.emplace_back(kHalves[i], kHalves[i + 1], kHalves[i + 2]);
  return rgb;
}

TEST(HalfRgbPixelsTest, NewPixelsAreBlack) {
  const HalfRgbPixels p(4);
  ASSERT_EQ(p.size(), 4u);
  EXPECT_FALSE(p.empty());
  for (glm::vec3 v : p) EXPECT_EQ(v, glm::vec3(0.0f));
  EXPECT_TRUE(HalfRgbPixels().empty());
}

// Every value a half can hold comes back exactly, through each way of reading.
TEST(HalfRgbPixelsTest, HalfValuesReadBackExactly) {
  const std::vector<glm::vec3> rgb = sample_pixels();
  const HalfRgbPixels p = filled(rgb);
  ASSERT_EQ(p.size(), rgb.size());
  for (std::size_t i = 0; i < rgb.size(); ++i) EXPECT_EQ(p[i], rgb[i]) << "pixel " << i;
  EXPECT_EQ(p.to_floats(), rgb);

  std::vector<float> row(3 * 3);
  p.read(2, 3, row.data());
  for (std::size_t i = 0; i < 3; ++i)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(row[3 * i + c], rgb[2 + i][c]) << "pixel " << 2 + i;

  std::size_t n = 0;
  for (glm::vec3 v : p) EXPECT_EQ(v, rgb[n++]);
  EXPECT_EQ(n, rgb.size());
}

TEST(HalfRgbPixelsTest, EqualityIsPixelForPixel) {
  const std::vector<glm::vec3> rgb = sample_pixels();
  const HalfRgbPixels a = filled(rgb);
  EXPECT_EQ(a, filled(rgb));
  std::vector<glm::vec3> other = rgb;
  other[3].y = 0.25f;
  EXPECT_NE(a, filled(other));
  EXPECT_NE(a, HalfRgbPixels(rgb.size()));
}

}  // namespace
}  // namespace ddish::raster
