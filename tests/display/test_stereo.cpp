// Stereo view sets: eye placement, zero disparity where it belongs, per-eye asymmetric frusta.
#include <cmath>

#include <gtest/gtest.h>

#include "display/stereo.h"
#include "display/stereo_output.h"
#include "projection.h"

namespace ddish::display {
namespace {

using test::project_direction;
using test::project_point;

BaseCamera camera() {
  BaseCamera b;
  b.eye = glm::vec3(0.5f, 1.6f, 3.0f);
  b.forward = glm::normalize(glm::vec3(-1.0f, -0.2f, -2.0f));
  b.up = glm::vec3(0.0f, 1.0f, 0.0f);
  b.fov_y = glm::radians(60.0f);
  b.focal_distance = 2.0f;
  return b;
}

TEST(Stereo, EyesAreIpdApartAlongRightLeftEyeFirst) {
  const BaseCamera b = camera();
  StereoParams p;
  p.ipd = 0.063f;
  const ViewSet set = stereo_views(b, p, 1440, 1600);
  ASSERT_EQ(set.size(), 2u);
  EXPECT_EQ(set.views[0].name, "left");
  EXPECT_EQ(set.views[1].name, "right");
  const glm::vec3 between = set.views[1].eye() - set.views[0].eye();
  EXPECT_NEAR(glm::length(between), 0.063f, 1e-6f);
  EXPECT_NEAR(glm::dot(between, b.axis_right()), 0.063f, 1e-6f);
  EXPECT_NEAR(glm::length(0.5f * (set.views[0].eye() + set.views[1].eye()) - b.eye), 0.0f, 1e-6f);
  EXPECT_EQ(set.layout.columns, 2);
  EXPECT_EQ(set.layout.width, 2880);
  EXPECT_EQ(set.layout.height, 1600);
}

TEST(Stereo, ParallelSymmetricEyesPutAPointAtInfinityOnTheSamePixel) {
  const BaseCamera b = camera();
  StereoParams p;
  p.converge = false;
  const ViewSet set = stereo_views(b, p, 1440, 1600);
  for (glm::vec3 dir : {b.axis_forward(), glm::normalize(b.axis_forward() + 0.3f * b.axis_right() -
                                                          0.2f * b.axis_up())}) {
    const glm::dvec2 l = project_direction(set.views[0], dir);
    const glm::dvec2 r = project_direction(set.views[1], dir);
    EXPECT_NEAR(l.x, r.x, 1e-3);
    EXPECT_NEAR(l.y, r.y, 1e-3);
  }
  // Straight ahead is the image centre.
  const glm::dvec2 c = project_direction(set.views[0], b.axis_forward());
  EXPECT_NEAR(c.x, 720.0, 1e-3);
  EXPECT_NEAR(c.y, 800.0, 1e-3);
}

TEST(Stereo, ConvergedEyesAgreeAtTheScreenAndSeeInfinityUncrossed) {
  const BaseCamera b = camera();
  StereoParams p;  // converged at the focal distance by default
  const ViewSet set = stereo_views(b, p, 800, 600);
  const glm::vec3 on_screen = b.eye + b.focal_distance * b.axis_forward() + 0.2f * b.axis_up();
  const glm::dvec2 l = project_point(set.views[0], on_screen);
  const glm::dvec2 r = project_point(set.views[1], on_screen);
  EXPECT_NEAR(l.x, r.x, 1e-3);
  EXPECT_NEAR(l.y, r.y, 1e-3);
  // Beyond the screen the left eye sees a point further left than the right eye does, by
  // IPD / (screen width) of the image width.
  const glm::dvec2 li = project_direction(set.views[0], b.axis_forward());
  const glm::dvec2 ri = project_direction(set.views[1], b.axis_forward());
  const double screen_width = 2.0 * (800.0 / 600.0) * b.focal_distance * std::tan(0.5 * b.fov_y);
  EXPECT_NEAR(ri.x - li.x, 0.063 / screen_width * 800.0, 1e-3);
}

TEST(Stereo, AsymmetricFieldOfViewPutsTheFrustumEdgesOnTheImageEdges) {
  const BaseCamera b = camera();
  StereoParams p;
  const EyeFov left{glm::radians(-50.0f), glm::radians(43.0f), glm::radians(47.0f),
                    glm::radians(-53.0f)};
  const EyeFov right{glm::radians(-43.0f), glm::radians(50.0f), glm::radians(47.0f),
                     glm::radians(-53.0f)};
  p.left_eye_fov = left;
  p.right_eye_fov = right;
  const ViewSet set = stereo_views(b, p, 1440, 1600);
  const glm::vec3 f = b.axis_forward(), rt = b.axis_right(), up = b.axis_up();
  for (int e = 0; e < 2; ++e) {
    const EyeFov& fov = e == 0 ? left : right;
    const scene::View& v = set.views[e];
    const glm::vec3 eye = v.eye();
    // Points 3 m out along each edge direction (horizontal edges on the eye's horizon, vertical
    // edges on its vertical centre line).
    auto at = [&](float tan_x, float tan_y) { return eye + 3.0f * (f + tan_x * rt + tan_y * up); };
    EXPECT_NEAR(project_point(v, at(std::tan(fov.left), 0.0f)).x, 0.0, 1e-3);
    EXPECT_NEAR(project_point(v, at(std::tan(fov.right), 0.0f)).x, 1440.0, 1e-3);
    EXPECT_NEAR(project_point(v, at(0.0f, std::tan(fov.up))).y, 0.0, 1e-3);      // top row
    EXPECT_NEAR(project_point(v, at(0.0f, std::tan(fov.down))).y, 1600.0, 1e-3);  // bottom
  }
  // Straight ahead is off-centre: 50° out vs 43° in puts it right of centre in the left eye.
  const double ahead_x = project_direction(set.views[0], f).x;
  const double expected = std::tan(glm::radians(50.0)) /
                          (std::tan(glm::radians(50.0)) + std::tan(glm::radians(43.0))) * 1440.0;
  EXPECT_NEAR(ahead_x, expected, 1e-3);
  EXPECT_NEAR(project_direction(set.views[1], f).x, 1440.0 - expected, 1e-3);
  EXPECT_NEAR(glm::length(set.views[1].eye() - set.views[0].eye()), 0.063f, 1e-6f);
}

TEST(Stereo, RejectsOneEyedFieldOfViewAndBadAngles) {
  const BaseCamera b = camera();
  StereoParams p;
  p.left_eye_fov = EyeFov{-0.8f, 0.7f, 0.8f, -0.9f};
  EXPECT_THROW(stereo_views(b, p, 64, 64), std::invalid_argument);
  p.right_eye_fov = EyeFov{0.7f, -0.8f, 0.8f, -0.9f};  // left > right
  EXPECT_THROW(stereo_views(b, p, 64, 64), std::invalid_argument);
  StereoParams q;
  q.ipd = -0.01f;
  EXPECT_THROW(stereo_views(b, q, 64, 64), std::invalid_argument);
}

TEST(StereoOutput, SideBySidePutsTheLeftEyeOnTheLeft) {
  std::vector<float> l(3 * 4 * 2, 0.25f), r(3 * 4 * 2, 0.75f);
  r[3 * (1 * 4 + 3) + 2] = 9.0f;  // right eye, pixel (3, 1), blue
  const RgbImage sbs = side_by_side(ConstRgbView{4, 2, l.data()}, ConstRgbView{4, 2, r.data()});
  ASSERT_EQ(sbs.width(), 8);
  ASSERT_EQ(sbs.height(), 2);
  EXPECT_FLOAT_EQ(sbs.pixel(3, 0)[0], 0.25f);
  EXPECT_FLOAT_EQ(sbs.pixel(4, 0)[0], 0.75f);
  EXPECT_FLOAT_EQ(sbs.pixel(7, 1)[2], 9.0f);
  EXPECT_THROW(side_by_side(ConstRgbView{4, 2, l.data()}, ConstRgbView{2, 4, r.data()}),
               std::invalid_argument);
}

}  // namespace
}  // namespace ddish::display
