// Quilt composition and naming.
#include <gtest/gtest.h>

#include "display/quilt.h"

namespace ddish::display {
namespace {

TEST(QuiltName, AspectIsTruncatedToTwoDecimalsWithoutTrailingZeros) {
  EXPECT_EQ(format_quilt_aspect(0.75f), "0.75");
  EXPECT_EQ(format_quilt_aspect(16.0f / 9.0f), "1.77");
  EXPECT_EQ(format_quilt_aspect(1.6f), "1.6");
  EXPECT_EQ(format_quilt_aspect(2.0f), "2");
  EXPECT_EQ(format_quilt_aspect(0.5625f), "0.56");
  EXPECT_EQ(format_quilt_aspect(0.7499999f), "0.75");
  EXPECT_EQ(format_quilt_aspect(1.0f / 3.0f), "0.33");
  EXPECT_EQ(format_quilt_aspect(1.05f), "1.05");
  EXPECT_THROW(format_quilt_aspect(0.0f), std::invalid_argument);
}

TEST(QuiltName, FollowsTheLayout) {
  EXPECT_EQ(quilt_file_name("cornell", layout_from_atlas(8, 6, 3360, 3360), 0.75f),
            "cornell_qs8x6a0.75.png");
  EXPECT_EQ(quilt_file_name("f0001", layout_from_tiles(8, 4, 1280, 720), 1280.0f / 720.0f,
                            ".exr"),
            "f0001_qs8x4a1.77.exr");
}

// A view whose every pixel is (index, row, column) so its placement can be read back.
std::vector<float> marked_view(int index, int w, int h) {
  std::vector<float> v(3 * std::size_t(w) * std::size_t(h));
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      float* p = &v[3 * (std::size_t(y) * w + x)];
      p[0] = float(index);
      p[1] = float(y);
      p[2] = float(x);
    }
  }
  return v;
}

TEST(Quilt, ViewZeroIsBottomLeftThenLeftToRightThenUp) {
  const QuiltLayout layout = layout_from_tiles(3, 2, 4, 5);
  std::vector<std::vector<float>> data;
  std::vector<ConstRgbView> views;
  for (int i = 0; i < 5; ++i) data.push_back(marked_view(i, 4, 5));  // one cell left empty
  for (const auto& d : data) views.push_back(ConstRgbView{4, 5, d.data()});
  const RgbImage q = compose_quilt(views, layout);
  ASSERT_EQ(q.width(), 12);
  ASSERT_EQ(q.height(), 10);
  // Bottom row of tiles (image rows 5..9) holds views 0, 1, 2; the top row views 3, 4, empty.
  EXPECT_FLOAT_EQ(q.pixel(0, 5)[0], 0.0f);
  EXPECT_FLOAT_EQ(q.pixel(4, 9)[0], 1.0f);
  EXPECT_FLOAT_EQ(q.pixel(11, 5)[0], 2.0f);
  EXPECT_FLOAT_EQ(q.pixel(0, 0)[0], 3.0f);
  EXPECT_FLOAT_EQ(q.pixel(7, 4)[0], 4.0f);
  // Inside a tile the view is not flipped: its row 0 (top) is the tile's top row.
  EXPECT_FLOAT_EQ(q.pixel(4 + 3, 5 + 0)[1], 0.0f);
  EXPECT_FLOAT_EQ(q.pixel(4 + 3, 5 + 4)[1], 4.0f);
  EXPECT_FLOAT_EQ(q.pixel(4 + 3, 5 + 4)[2], 3.0f);
  // The empty cell is black.
  EXPECT_FLOAT_EQ(q.pixel(10, 2)[0], 0.0f);
  EXPECT_FLOAT_EQ(q.pixel(10, 2)[1], 0.0f);
  EXPECT_FLOAT_EQ(q.pixel(10, 2)[2], 0.0f);
}

TEST(Quilt, SpareColumnAndRowOfANonDivisibleAtlasStayBlack) {
  // 11 × 11 for 2 × 2 tiles: tiles are 5 × 5, hugging the bottom-left corner.
  const QuiltLayout layout = layout_from_atlas(2, 2, 11, 11);
  EXPECT_EQ(layout.tile_width, 5);
  std::vector<std::vector<float>> data;
  std::vector<ConstRgbView> views;
  for (int i = 0; i < 4; ++i) data.push_back(std::vector<float>(75, float(i + 1)));
  for (const auto& d : data) views.push_back(ConstRgbView{5, 5, d.data()});
  const RgbImage q = compose_quilt(views, layout);
  EXPECT_FLOAT_EQ(q.pixel(0, 10)[0], 1.0f);  // bottom-left pixel: view 0
  EXPECT_FLOAT_EQ(q.pixel(9, 1)[0], 4.0f);   // view 3 reaches the second row from the top
  for (int i = 0; i < 11; ++i) {
    EXPECT_FLOAT_EQ(q.pixel(10, i)[0], 0.0f);  // right column
    EXPECT_FLOAT_EQ(q.pixel(i, 0)[0], 0.0f);   // top row
  }
}

TEST(Quilt, RejectsMisSizedViewsAndTooManyViews) {
  const QuiltLayout layout = layout_from_tiles(2, 1, 4, 4);
  std::vector<float> small(3 * 3 * 4), fine(3 * 4 * 4);
  std::vector<ConstRgbView> wrong{ConstRgbView{3, 4, small.data()}};
  EXPECT_THROW(compose_quilt(wrong, layout), std::invalid_argument);
  std::vector<ConstRgbView> three(3, ConstRgbView{4, 4, fine.data()});
  EXPECT_THROW(compose_quilt(three, layout), std::invalid_argument);
  RgbImage out(7, 4);
  std::vector<ConstRgbView> one{ConstRgbView{4, 4, fine.data()}};
  EXPECT_THROW(compose_quilt(one, layout, out.view()), std::invalid_argument);
  EXPECT_THROW(layout_from_atlas(5, 9, 4, 4096), std::invalid_argument);
}

}  // namespace
}  // namespace ddish::display
