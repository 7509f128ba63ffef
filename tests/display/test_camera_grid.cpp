// Camera grids: placement, order, recentering.
#include <cmath>

#include <gtest/gtest.h>

#include "display/camera_grid.h"
#include "projection.h"

namespace ddish::display {
namespace {

using test::project_point;

BaseCamera camera() {
  BaseCamera b;
  b.eye = glm::vec3(-1.0f, 2.0f, 6.0f);
  b.forward = glm::normalize(glm::vec3(1.0f, -1.0f, -6.0f));
  b.fov_y = glm::radians(35.0f);
  b.focal_distance = 6.0f;
  return b;
}

TEST(CameraGrid, CamerasSitOnASpacedPlaneGridRowByRowFromTheBottomLeft) {
  const BaseCamera b = camera();
  GridParams g;
  g.columns = 4;
  g.rows = 3;
  g.spacing = 0.1f;
  const ViewSet set = camera_grid(b, g, layout_from_tiles(4, 3, 32, 18), 16.0f / 9.0f);
  ASSERT_EQ(set.size(), 12u);
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 4; ++col) {
      const glm::vec3 off = set.views[row * 4 + col].eye() - b.eye;
      EXPECT_NEAR(glm::dot(off, b.axis_right()), (col - 1.5f) * 0.1f, 1e-5f);
      EXPECT_NEAR(glm::dot(off, b.axis_up()), (row - 1.0f) * 0.1f, 1e-5f);
      EXPECT_NEAR(glm::dot(off, b.axis_forward()), 0.0f, 1e-5f);
    }
  }
  EXPECT_EQ(set.views[0].name, "view_00");
  EXPECT_EQ(set.views[11].name, "view_11");
}

TEST(CameraGrid, FrustaRecentreOnThePlaneAtTheRecenteringDistance) {
  const BaseCamera b = camera();
  GridParams g;
  g.columns = 5;
  g.rows = 3;
  g.spacing_ratio = 0.05f;
  g.recenter_distance = 4.0f;
  const ViewSet set = camera_grid(b, g, layout_from_tiles(5, 3, 160, 90), 16.0f / 9.0f);
  // Spacing follows the ratio: 0.05 · 4 = 0.2 between neighbours.
  EXPECT_NEAR(glm::length(set.views[1].eye() - set.views[0].eye()), 0.2f, 1e-5f);
  const float half_h = 4.0f * std::tan(0.5f * b.fov_y);
  const glm::vec3 center = b.eye + 4.0f * b.axis_forward();
  const glm::vec3 p = center + 0.4f * half_h * b.axis_right() - 0.6f * half_h * b.axis_up();
  const glm::dvec2 expected((0.4 / (16.0 / 9.0) + 1.0) * 0.5 * 160.0, (0.6 + 1.0) * 0.5 * 90.0);
  for (const scene::View& v : set.views) {
    const glm::dvec2 px = project_point(v, p);
    EXPECT_NEAR(px.x, expected.x, 1e-3) << v.name;
    EXPECT_NEAR(px.y, expected.y, 1e-3) << v.name;
  }
  // Off the plane the views disagree both ways: a grid has vertical parallax too.
  const glm::vec3 near = b.eye + 2.0f * b.axis_forward();
  const glm::dvec2 bottom_left = project_point(set.views[0], near);
  const glm::dvec2 top_right = project_point(set.views[14], near);
  EXPECT_GT(bottom_left.x, top_right.x);  // nearer point: moves against the camera (left)
  EXPECT_GT(top_right.y, bottom_left.y);  // and down the image as the camera moves up
}

TEST(CameraGrid, RejectsAGridLargerThanTheAtlas) {
  GridParams g;
  g.columns = 3;
  g.rows = 3;
  EXPECT_THROW(camera_grid(camera(), g, layout_from_tiles(4, 2, 8, 8), 1.0f),
               std::invalid_argument);
  g.columns = 0;
  EXPECT_THROW(camera_grid(camera(), g, layout_from_tiles(4, 2, 8, 8), 1.0f),
               std::invalid_argument);
}

}  // namespace
}  // namespace ddish::display
