#include "metrics/views.h"

#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

#include "metrics/image_io.h"
#include "test_util.h"

namespace ddish::metrics {
namespace {

TEST(Views, QuiltLayoutFromName) {
  auto q = quilt_layout_from_name("portrait_qs8x6a0.75.png");
  ASSERT_TRUE(q);
  EXPECT_EQ(q->cols, 8);
  EXPECT_EQ(q->rows, 6);
  EXPECT_EQ(q->views(), 48);
  EXPECT_FALSE(quilt_layout_from_name("reference.png"));
  EXPECT_EQ(parse_quilt_layout("5x9").rows, 9);
  EXPECT_THROW(parse_quilt_layout("5by9"), std::invalid_argument);
}

TEST(Views, SplitQuiltStartsBottomLeft) {
  // A 3x2 quilt of 2x1 views; each view is filled with its index.
  QuiltLayout layout{3, 2};
  Image quilt(6, 2);
  for (int v = 0; v < 6; ++v) {
    int col = v % 3, row_from_top = 1 - v / 3;
    for (int x = 0; x < 2; ++x) quilt.at(col * 2 + x, row_from_top) = glm::vec3(float(v));
  }
  std::vector<Image> views = split_quilt(quilt, layout);
  ASSERT_EQ(views.size(), 6u);
  for (int v = 0; v < 6; ++v) {
    EXPECT_EQ(views[v].width(), 2);
    EXPECT_EQ(views[v].height(), 1);
    EXPECT_EQ(views[v].at(1, 0).x, float(v));
  }
  EXPECT_EQ(split_quilt(quilt, layout, 4).size(), 4u);
  EXPECT_THROW(split_quilt(quilt, layout, 7), std::invalid_argument);
  EXPECT_THROW(split_quilt(Image(7, 2), layout), std::invalid_argument);
}

TEST(Views, CompareQuiltsPerView) {
  QuiltLayout layout{2, 1};
  Image a(4, 2, glm::vec3(0.5f));
  Image b = a;
  b.at(3, 1) = glm::vec3(0.0f);  // in view 1 (the right half)
  auto errs = compare_quilts(a, b, layout);
  ASSERT_EQ(errs.size(), 2u);
  EXPECT_TRUE(std::isinf(errs[0].errors.psnr));
  EXPECT_NEAR(errs[1].errors.rmse, std::sqrt(0.25 * 3 / 12.0), 1e-7);
  ImageErrors mean = mean_errors(errs);
  EXPECT_NEAR(mean.rmse, 0.5 * errs[1].errors.rmse, 1e-12);
}

TEST(Views, CompareDirectoriesByName) {
  auto root = testing::scratch_dir();
  std::filesystem::create_directories(root / "out");
  std::filesystem::create_directories(root / "ref");
  write_exr(root / "out" / "view_1.exr", Image(4, 4, glm::vec3(1.0f)));
  write_exr(root / "ref" / "view_1.exr", Image(4, 4, glm::vec3(0.5f)));
  write_exr(root / "out" / "view_0.exr", Image(4, 4, glm::vec3(0.25f)));
  write_exr(root / "ref" / "view_0.exr", Image(4, 4, glm::vec3(0.25f)));
  auto errs = compare_directories(root / "out", root / "ref");
  ASSERT_EQ(errs.size(), 2u);
  EXPECT_EQ(errs[0].name, "view_0.exr");
  EXPECT_EQ(errs[0].errors.rmse, 0.0);
  EXPECT_NEAR(errs[1].errors.rmse, 0.5, 1e-7);

  write_exr(root / "out" / "view_2.exr", Image(4, 4));
  EXPECT_THROW(compare_directories(root / "out", root / "ref"), std::invalid_argument);
  write_exr(root / "ref" / "view_2.exr", Image(4, 5));
  try {
    compare_directories(root / "out", root / "ref");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("view_2.exr"), std::string::npos);
  }
}

}  // namespace
}  // namespace ddish::metrics
