// The shadow-map layout on the CPU: cascade splits, and that every layer's matrix actually
// covers what it is meant to (the view frustum inside the scene for cascades, the cone for a
// spot light, every direction for a point light's six faces).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "raster/shadow_layout.h"
#include "scene/scene.h"
#include "scene/view.h"

namespace ddish::raster {
namespace {

bool inside(const ShadowLayerData& layer, const glm::vec3& p) {
  const glm::vec4 clip = layer.light_view_proj * glm::vec4(p, 1.0f);
  const glm::vec3 ndc = glm::vec3(clip) / clip.w;
  return clip.w > 0.0f && std::abs(ndc.x) <= 1.0f && std::abs(ndc.y) <= 1.0f && ndc.z >= 0.0f &&
         ndc.z <= 1.0f;
}

const scene::Aabb kBounds{{-5.0f, 0.0f, -5.0f}, {5.0f, 3.0f, 5.0f}};

TEST(ShadowLayout, CascadeSplitsIncreaseToFar) {
  const std::vector<float> s = cascade_splits(0.1f, 50.0f, 4, 0.6f);
  ASSERT_EQ(s.size(), 4u);
  EXPECT_GT(s[0], 0.1f);
  for (std::size_t i = 1; i < s.size(); ++i) EXPECT_GT(s[i], s[i - 1]);
  EXPECT_FLOAT_EQ(s.back(), 50.0f);
  EXPECT_THROW(cascade_splits(0.1f, 50.0f, 5, 0.5f), std::invalid_argument);
}

TEST(ShadowLayout, CascadesCoverTheVisibleScene) {
  scene::Light sun;
  sun.type = scene::LightType::Directional;
  sun.direction = glm::normalize(glm::vec3(-0.4f, -1.0f, 0.3f));
  const scene::View view = scene::look_at_view({0, 1.5f, 4.5f}, {0, 1, 0}, {0, 1, 0}, 1.0f, 64, 64);
  const ShadowLayout layout = layout_shadows(std::span(&sun, 1), std::span(&view, 1), kBounds, {});
  ASSERT_EQ(layout.layers.size(), 3u);
  EXPECT_EQ(layout.lights[0].spot_shadow.z, 0.0f);
  EXPECT_EQ(layout.lights[0].spot_shadow.w, 3.0f);
  // Random points seen by the camera inside the bounds are in at least one cascade.
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  int tested = 0;
  for (int i = 0; i < 4000; ++i) {
    const scene::Ray r = scene::view_ray(view, u(rng) * 64.0f, u(rng) * 64.0f);
    const glm::vec3 p = r.origin + r.direction * (0.05f + u(rng) * 12.0f);
    if (!kBounds.contains(p)) continue;
    ++tested;
    bool covered = false;
    for (const ShadowLayerData& l : layout.layers) covered = covered || inside(l, p);
    EXPECT_TRUE(covered) << p.x << "," << p.y << "," << p.z;
  }
  EXPECT_GT(tested, 1000);
}

TEST(ShadowLayout, SpotAndPointLayersCoverTheirLight) {
  scene::Light spot;
  spot.type = scene::LightType::Spot;
  spot.position = {0, 2.5f, 0};
  spot.direction = {0, -1, 0};
  spot.outer_cone = 0.7f;
  scene::Light point;
  point.type = scene::LightType::Point;
  point.position = {1, 1.5f, -1};
  const std::vector<scene::Light> lights{spot, point};
  const scene::View view = scene::look_at_view({0, 1.5f, 4.5f}, {0, 1, 0}, {0, 1, 0}, 1.0f, 64, 64);
  const ShadowLayout layout = layout_shadows(lights, std::span(&view, 1), kBounds, {});
  ASSERT_EQ(layout.layers.size(), 7u);  // 1 spot + 6 cube faces
  EXPECT_EQ(layout.lights[1].spot_shadow.z, 1.0f);
  EXPECT_EQ(layout.lights[1].spot_shadow.w, 6.0f);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (int i = 0; i < 2000; ++i) {
    const glm::vec3 d = glm::normalize(glm::vec3(u(rng), u(rng), u(rng)));
    const float dist = 0.2f + 2.0f * std::abs(u(rng));
    // Spot: points inside the cone are in its one layer.
    if (glm::dot(d, spot.direction) > std::cos(spot.outer_cone)) {
      EXPECT_TRUE(inside(layout.layers[0], spot.position + d * dist));
    }
    // Point: the face of the major axis (forward.frag's choice) holds the point.
    const glm::vec3 a = glm::abs(d);
    int face = a.x >= a.y && a.x >= a.z ? (d.x >= 0 ? 0 : 1) : (a.y >= a.z ? (d.y >= 0 ? 2 : 3) : (d.z >= 0 ? 4 : 5));
    EXPECT_TRUE(inside(layout.layers[1 + std::size_t(face)], point.position + d * dist)) << face;
  }
  // With shadows switched off, lights get no layers and say so.
  ShadowSettings off;
  off.enabled = false;
  off.point_shadows = false;
  const ShadowLayout none = layout_shadows(lights, std::span(&view, 1), kBounds, off);
  EXPECT_TRUE(none.layers.empty());
  EXPECT_EQ(none.lights[0].spot_shadow.z, -1.0f);
}

}  // namespace
}  // namespace ddish::raster
