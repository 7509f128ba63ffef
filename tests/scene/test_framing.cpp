// The framing camera (scene/framing.h) for scenes without one: the bounding sphere is in view,
// its silhouette spans kFramingFill of the narrower field, and the view is three-quarter.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <glm/glm.hpp>

#include "scene/framing.h"
#include "scene/gltf_loader.h"
#include "scene/view.h"

using namespace ddish;

namespace {

scene::Scene open_sphere() {
  return scene::load_scene(std::string(DDISH_SOURCE_DIR) + "/scenes/open_sphere.gltf");
}

// Angle between the camera's axis and the sphere's silhouette (its tangent cone).
float silhouette_angle(const scene::Camera& c, const scene::Sphere& s) {
  return std::asin(s.radius / glm::length(s.center - c.eye));
}

}  // namespace

TEST(Framing, BoundingSphereOfASphereMeshIsTheSphere) {
  // open_sphere: radius 0.5 around (0.3, 2, -0.4) (scripts/make_scenes.py); its vertices lie on
  // the sphere, so the farthest one is at the radius, a box corner would be at sqrt(3) x 0.5.
  const scene::Sphere s = bounding_sphere(open_sphere());
  EXPECT_NEAR(s.center.x, 0.3f, 1e-5f);
  EXPECT_NEAR(s.center.y, 2.0f, 1e-5f);
  EXPECT_NEAR(s.center.z, -0.4f, 1e-5f);
  EXPECT_NEAR(s.radius, 0.5f, 1e-5f);
}

TEST(Framing, SilhouetteFillsTheNarrowerField) {
  const scene::Sphere sphere{{0.3f, 2.0f, -0.4f}, 0.5f};
  const float fov = glm::radians(45.0f);
  // Landscape and square views are limited vertically, portrait ones horizontally.
  for (float aspect : {1.0f, 16.0f / 9.0f, 0.75f, 0.5f}) {
    const scene::Camera c = scene::framing_camera(sphere, fov, aspect);
    const float half = std::min(0.5f * fov, std::atan(std::tan(0.5f * fov) * aspect));
    EXPECT_NEAR(std::tan(silhouette_angle(c, sphere)), scene::kFramingFill * std::tan(half), 1e-5f)
        << "aspect " << aspect;
    // Aimed at the centre, +Y up, the sphere between the clip planes.
    const glm::vec3 to_center = glm::normalize(sphere.center - c.eye);
    EXPECT_NEAR(glm::dot(glm::normalize(c.forward), to_center), 1.0f, 1e-6f);
    const float d = glm::length(sphere.center - c.eye);
    EXPECT_LT(c.znear, d - sphere.radius);
    EXPECT_GT(c.zfar, d + sphere.radius);
    EXPECT_EQ(c.node, -1);
    EXPECT_EQ(c.name, scene::kFramingCameraName);
  }
}

TEST(Framing, ThreeQuarterViewFromFrontRightAbove) {
  const scene::Camera c = scene::framing_camera({{0.0f, 0.0f, 0.0f}, 1.0f}, 0.8f, 1.0f);
  const glm::vec3 to_eye = glm::normalize(c.eye);
  EXPECT_NEAR(std::asin(to_eye.y), glm::radians(scene::kFramingElevationDeg), 1e-5f);
  EXPECT_NEAR(std::atan2(to_eye.x, to_eye.z), glm::radians(scene::kFramingAzimuthDeg), 1e-5f);
  EXPECT_EQ(c.up, glm::vec3(0.0f, 1.0f, 0.0f));
}

TEST(Framing, EveryCornerOfABoxProjectsInsideTheImage) {
  // The box's own corners lie on its bounding sphere: the tightest case.
  scene::Sphere s{{1.0f, -2.0f, 3.0f}, std::sqrt(3.0f)};
  for (float aspect : {1.0f, 2.0f, 0.5f}) {
    const scene::Camera c = scene::framing_camera(s, glm::radians(45.0f), aspect);
    const int w = aspect >= 1.0f ? int(200 * aspect) : 200, h = aspect >= 1.0f ? 200 : int(200 / aspect);
    const scene::View v = scene::camera_view(c, w, h);
    for (int i = 0; i < 8; ++i) {
      const glm::vec3 p = s.center + glm::vec3(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
      const glm::vec4 clip = v.projection * v.view * glm::vec4(p, 1.0f);
      ASSERT_GT(clip.w, 0.0f);
      EXPECT_LT(std::abs(clip.x / clip.w), scene::kFramingFill + 1e-4f) << "aspect " << aspect;
      EXPECT_LT(std::abs(clip.y / clip.w), scene::kFramingFill + 1e-4f) << "aspect " << aspect;
      EXPECT_GT(clip.z / clip.w, 0.0f);
      EXPECT_LT(clip.z / clip.w, 1.0f);
    }
  }
}

TEST(Framing, PoseLeavesACameraOutsideTheHierarchyWhereItIs) {
  scene::Scene s = open_sphere();
  ASSERT_TRUE(s.cameras.empty());
  s.cameras.push_back(scene::framing_camera(bounding_sphere(s), 0.8f, 1.0f));
  const glm::vec3 eye = s.cameras[0].eye;
  s.pose(1.0);
  EXPECT_EQ(s.cameras[0].eye, eye);
  EXPECT_EQ(s.default_camera(), &s.cameras[0]);
}

TEST(Framing, EmptySceneFramesAUnitSphereAtTheOrigin) {
  const scene::Scene empty;
  const scene::Sphere s = bounding_sphere(empty);
  EXPECT_EQ(s.radius, 0.0f);
  const scene::Camera c = scene::framing_camera(s, 0.8f, 1.0f);
  EXPECT_TRUE(std::isfinite(c.eye.x) && glm::length(c.eye) > 1.0f);
}
