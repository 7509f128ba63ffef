// The base camera: built from a scene camera, its default focal distance, its validation, and
// the single view made from it.
#include <cmath>

#include <gtest/gtest.h>

#include "display/single_view.h"
#include "projection.h"
#include "scene/scene.h"

namespace ddish::display {
namespace {

scene::Scene box_scene(const glm::vec3& min, const glm::vec3& max) {
  scene::Scene s;
  scene::Mesh m;
  m.bounds.expand(min);
  m.bounds.expand(max);
  s.meshes.push_back(m);
  scene::Instance inst;
  inst.mesh = 0;
  s.instances.push_back(inst);
  return s;
}

TEST(BaseCamera, FocalDistanceIsTheDepthOfTheSceneCentre) {
  const scene::Scene s = box_scene(glm::vec3(-1.0f, 0.0f, -3.0f), glm::vec3(1.0f, 2.0f, -1.0f));
  // Centre (0, 1, -2); seen from (3, 1, 2) looking down -Z it is 4 deep (not 5 away).
  EXPECT_NEAR(focal_distance_to_scene_center(s, glm::vec3(3.0f, 1.0f, 2.0f),
                                             glm::vec3(0.0f, 0.0f, -2.0f)),
              4.0f, 1e-6f);
  // Behind the camera: the straight-line distance instead.
  EXPECT_NEAR(focal_distance_to_scene_center(s, glm::vec3(3.0f, 1.0f, 2.0f),
                                             glm::vec3(0.0f, 0.0f, 1.0f)),
              5.0f, 1e-6f);
  EXPECT_FLOAT_EQ(focal_distance_to_scene_center(scene::Scene{}, glm::vec3(0.0f),
                                                 glm::vec3(0.0f, 0.0f, -1.0f)),
                  1.0f);
}

TEST(BaseCamera, FromASceneCameraKeepsItsPoseAndField) {
  scene::Camera c;
  c.eye = glm::vec3(1.0f, 2.0f, 3.0f);
  c.forward = glm::vec3(0.0f, 0.0f, -1.0f);
  c.yfov = 0.9f;
  c.znear = 0.05f;
  c.zfar = 50.0f;
  const BaseCamera b = base_camera(c, 7.0f);
  EXPECT_EQ(b.eye, c.eye);
  EXPECT_FLOAT_EQ(b.fov_y, 0.9f);
  EXPECT_FLOAT_EQ(b.focal_distance, 7.0f);
  EXPECT_FLOAT_EQ(b.znear, 0.05f);
  // The single view of it matches the scene's own camera view.
  const ViewSet set = single_view(b, 64, 32);
  const scene::View ref = scene::camera_view(c, 64, 32);
  for (int col = 0; col < 4; ++col) {
    for (int row = 0; row < 4; ++row) {
      EXPECT_NEAR(set.views[0].projection[col][row], ref.projection[col][row], 1e-5f);
      EXPECT_NEAR(set.views[0].view[col][row], ref.view[col][row], 1e-5f);
    }
  }
  EXPECT_FLOAT_EQ(set.aspect, 2.0f);
}

TEST(BaseCamera, DegenerateCamerasAreRefused) {
  BaseCamera b;
  b.forward = glm::vec3(0.0f);
  EXPECT_THROW(b.validate(), std::invalid_argument);
  b = BaseCamera{};
  b.up = glm::vec3(0.0f, 0.0f, 2.0f);  // parallel to forward
  EXPECT_THROW(b.validate(), std::invalid_argument);
  b = BaseCamera{};
  b.focal_distance = 0.0f;
  EXPECT_THROW(b.validate(), std::invalid_argument);
  b = BaseCamera{};
  b.fov_y = 3.2f;
  EXPECT_THROW(b.validate(), std::invalid_argument);
  EXPECT_NO_THROW(BaseCamera{}.validate());
}

TEST(BaseCamera, ViewNamesSortInViewOrder) {
  EXPECT_EQ(indexed_view_name(7, 48), "view_07");
  EXPECT_EQ(indexed_view_name(47, 48), "view_47");
  EXPECT_EQ(indexed_view_name(3, 5), "view_3");
  EXPECT_EQ(indexed_view_name(12, 101), "view_012");
}

}  // namespace
}  // namespace ddish::display
