// The Looking Glass light-field rig: shared focal plane, parallax direction, view order.
#include <cmath>

#include <gtest/gtest.h>

#include "display/lightfield_rig.h"
#include "display/quilt_layout.h"
#include "projection.h"

namespace ddish::display {
namespace {

using test::project_point;

// A camera that is deliberately not axis-aligned, so a mix-up of axes shows.
BaseCamera tilted_camera() {
  BaseCamera b;
  b.eye = glm::vec3(2.0f, 1.5f, 4.0f);
  b.forward = glm::normalize(glm::vec3(0.0f, 0.5f, 0.0f) - b.eye);
  b.up = glm::vec3(0.0f, 1.0f, 0.0f);
  b.fov_y = glm::radians(40.0f);
  b.focal_distance = 4.5f;
  return b;
}

const QuiltLayout kPortrait = layout_from_atlas(8, 6, 3360, 3360);

ViewSet portrait_rig(const BaseCamera& b) {
  LightFieldParams p;
  p.views = 48;
  p.view_cone = glm::radians(40.0f);
  return lightfield_rig(b, p, kPortrait, 0.75f);
}

TEST(LightFieldRig, ViewAnglesSpanTheConeLeftToRight) {
  const float cone = glm::radians(40.0f);
  EXPECT_FLOAT_EQ(lightfield_view_angle(0, 48, cone), -0.5f * cone);
  EXPECT_FLOAT_EQ(lightfield_view_angle(47, 48, cone), 0.5f * cone);
  EXPECT_NEAR(lightfield_view_angle(1, 3, cone), 0.0f, 1e-7);
  EXPECT_FLOAT_EQ(lightfield_view_angle(0, 1, cone), 0.0f);
}

TEST(LightFieldRig, CamerasMoveAlongRightByDistanceTimesTanTheta) {
  const BaseCamera b = tilted_camera();
  const ViewSet set = portrait_rig(b);
  ASSERT_EQ(set.size(), 48u);
  for (int i = 0; i < 48; ++i) {
    const glm::vec3 offset = set.views[i].eye() - b.eye;
    const float expected =
        b.focal_distance * std::tan(lightfield_view_angle(i, 48, glm::radians(40.0f)));
    EXPECT_NEAR(glm::dot(offset, b.axis_right()), expected, 1e-4f) << "view " << i;
    EXPECT_NEAR(glm::length(offset - expected * b.axis_right()), 0.0f, 1e-4f) << "view " << i;
    EXPECT_EQ(set.views[i].width, 420);
    EXPECT_EQ(set.views[i].height, 560);
  }
  // 4.5 · tan(20°) = 1.6379 either side.
  EXPECT_NEAR(glm::dot(set.views[0].eye() - b.eye, b.axis_right()), -1.63786f, 1e-4f);
}

TEST(LightFieldRig, NoToeInEveryCameraLooksAlongTheBaseForward) {
  const BaseCamera b = tilted_camera();
  for (const scene::View& v : portrait_rig(b).views) {
    // The camera's -Z axis in world space is the third row of the view matrix, negated.
    const glm::vec3 looks(-v.view[0][2], -v.view[1][2], -v.view[2][2]);
    EXPECT_NEAR(glm::length(looks - b.axis_forward()), 0.0f, 1e-5f);
  }
}

TEST(LightFieldRig, PointsOnTheFocalPlaneLandOnTheSamePixelInEveryView) {
  const BaseCamera b = tilted_camera();
  const ViewSet set = portrait_rig(b);
  const glm::vec3 focal_center = b.eye + b.focal_distance * b.axis_forward();
  const float half_h = b.focal_distance * std::tan(0.5f * b.fov_y);
  for (glm::vec2 ab : {glm::vec2(0.0f), glm::vec2(0.3f, -0.2f), glm::vec2(-0.7f, 0.9f)}) {
    const glm::vec3 p =
        focal_center + ab.x * 0.75f * half_h * b.axis_right() + ab.y * half_h * b.axis_up();
    const glm::dvec2 first = project_point(set.views[0], p);
    // Where it must be: the same place in the focal rectangle as (ab) says, row 0 at the top.
    EXPECT_NEAR(first.x, (ab.x + 1.0) * 0.5 * 420.0, 1e-3);
    EXPECT_NEAR(first.y, (1.0 - ab.y) * 0.5 * 560.0, 1e-3);
    for (const scene::View& v : set.views) {
      const glm::dvec2 px = project_point(v, p);
      EXPECT_NEAR(px.x, first.x, 1e-3) << v.name;
      EXPECT_NEAR(px.y, first.y, 1e-3) << v.name;
    }
  }
}

// Derivation (docs/displays.md): camera i at lateral offset xᵢ sees a point at lateral position
// p and depth z at focal-rectangle coordinate (p·d/z + xᵢ·(1 − d/z)) / w, so from view to view
// it moves by Δx·(1 − d/z)/w: against the cameras' motion (left, pixel x decreasing) when the
// point is nearer than the focal plane (z < d), with them (right) when it is beyond (z > d).
TEST(LightFieldRig, NearPointsMoveLeftAndFarPointsRightAsTheCamerasMoveRight) {
  const BaseCamera b = tilted_camera();
  const ViewSet set = portrait_rig(b);
  const float d = b.focal_distance;
  const float half_w = 0.75f * d * std::tan(0.5f * b.fov_y);
  for (float z : {0.6f * d, 2.0f * d}) {
    const glm::vec3 p = b.eye + z * b.axis_forward() + 0.1f * b.axis_right();
    const glm::dvec2 first = project_point(set.views[0], p);
    const float x0 = glm::dot(set.views[0].eye() - b.eye, b.axis_right());
    double previous = first.x;
    for (int i = 1; i < 48; ++i) {
      const glm::dvec2 px = project_point(set.views[i], p);
      if (z < d) {
        EXPECT_LT(px.x, previous) << "near point, view " << i;
      } else {
        EXPECT_GT(px.x, previous) << "far point, view " << i;
      }
      const float xi = glm::dot(set.views[i].eye() - b.eye, b.axis_right());
      const double expected_shift = (xi - x0) * (1.0 - d / z) / half_w * 0.5 * 420.0;
      EXPECT_NEAR(px.x - first.x, expected_shift, 2e-3) << "view " << i;
      EXPECT_NEAR(px.y, first.y, 1e-3) << "horizontal parallax only, view " << i;
      previous = px.x;
    }
  }
}

TEST(LightFieldRig, ViewZeroIsTheLeftmostCameraInTheBottomLeftTile) {
  const BaseCamera b = tilted_camera();
  const ViewSet set = portrait_rig(b);
  const glm::vec3 r = b.axis_right();
  for (std::size_t i = 1; i < set.size(); ++i) {
    EXPECT_LT(glm::dot(set.views[i - 1].eye(), r), glm::dot(set.views[i].eye(), r));
  }
  const TileRect t0 = set.layout.tile(0);
  EXPECT_EQ(t0.x, 0);
  EXPECT_EQ(t0.y, 3360 - 560);  // the bottom row of tiles (image row 0 is the top)
  const TileRect t7 = set.layout.tile(7);
  EXPECT_EQ(t7.x, 7 * 420);
  EXPECT_EQ(t7.y, 3360 - 560);
  const TileRect t8 = set.layout.tile(8);  // second row, going upwards
  EXPECT_EQ(t8.x, 0);
  EXPECT_EQ(t8.y, 3360 - 2 * 560);
  EXPECT_EQ(set.layout.tile(47).y, 0);
}

TEST(LightFieldRig, OwnFieldOfViewKeepsTheBaseFraming) {
  BaseCamera b = tilted_camera();
  LightFieldParams p;
  p.views = 5;
  p.fov_y = glm::radians(14.0f);
  const ViewSet set = lightfield_rig(b, p, layout_from_tiles(5, 1, 64, 48), 4.0f / 3.0f);
  // The base camera's focal-plane corner projects to the image corner in every view.
  const float half_h = b.focal_distance * std::tan(0.5f * b.fov_y);
  const glm::vec3 corner = b.eye + b.focal_distance * b.axis_forward() +
                           (4.0f / 3.0f) * half_h * b.axis_right() + half_h * b.axis_up();
  for (const scene::View& v : set.views) {
    const glm::dvec2 px = project_point(v, corner);
    EXPECT_NEAR(px.x, 64.0, 1e-3);
    EXPECT_NEAR(px.y, 0.0, 1e-3);
  }
  // The rig stands back to d = half height / tan(7°) from the focal plane.
  const float d = half_h / std::tan(glm::radians(7.0f));
  EXPECT_NEAR(glm::dot(b.eye + b.focal_distance * b.axis_forward() - set.views[2].eye(),
                       b.axis_forward()),
              d, 1e-3f);
}

TEST(LightFieldRig, RejectsMoreViewsThanCellsAndBadParameters) {
  const BaseCamera b = tilted_camera();
  LightFieldParams p;
  p.views = 49;
  EXPECT_THROW(lightfield_rig(b, p, kPortrait, 0.75f), std::invalid_argument);
  p.views = 0;
  EXPECT_THROW(lightfield_rig(b, p, kPortrait, 0.75f), std::invalid_argument);
  p.views = 48;
  p.view_cone = -0.1f;
  EXPECT_THROW(lightfield_rig(b, p, kPortrait, 0.75f), std::invalid_argument);
  BaseCamera bad = b;
  bad.up = bad.forward;
  p.view_cone = 0.5f;
  EXPECT_THROW(lightfield_rig(bad, p, kPortrait, 0.75f), std::invalid_argument);
}

}  // namespace
}  // namespace ddish::display
