// The scenes in scenes/ (written by scripts/make_scenes.py): contents, plans, and closure: rays
// from a point inside a room must all hit front faces, rays from inside a solid all back faces,
// which is what probe classification relies on.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include "scene/features.h"
#include "scene/gltf_loader.h"

using namespace ddish;

namespace {

scene::Scene bundled(const char* name) {
  return scene::load_scene(std::string(DDISH_SOURCE_DIR) + "/scenes/" + name);
}

struct Hit {
  float t;
  bool front;
};

// Brute-force nearest hit of a ray against every triangle (the scenes have a few hundred).
std::optional<Hit> nearest_hit(const scene::Scene& s, glm::vec3 o, glm::vec3 d) {
  std::optional<Hit> best;
  for (const auto& inst : s.instances) {
    const scene::Mesh& m = s.meshes[std::size_t(inst.mesh)];
    for (std::size_t i = 0; i < m.indices.size(); i += 3) {
      glm::vec3 p[3];
      for (int k = 0; k < 3; ++k)
        p[k] =
            glm::vec3(inst.transform * glm::vec4(m.positions[m.indices[i + std::size_t(k)]], 1.0f));
      glm::vec3 e1 = p[1] - p[0], e2 = p[2] - p[0];
      glm::vec3 q = glm::cross(d, e2);
      float det = glm::dot(e1, q);
      if (std::abs(det) < 1e-12f) continue;
      glm::vec3 r = o - p[0];
      float u = glm::dot(r, q) / det;
      glm::vec3 w = glm::cross(r, e1);
      float v = glm::dot(d, w) / det;
      float t = glm::dot(e2, w) / det;
      if (u < 0 || v < 0 || u + v > 1 || t <= 1e-5f) continue;
      if (!best || t < best->t) best = Hit{t, glm::dot(glm::cross(e1, e2), d) < 0.0f};
    }
  }
  return best;
}

struct Sides {
  int front = 0, back = 0, miss = 0;
};

// Where rays in a Fibonacci sphere of directions from `origin` end up.
Sides cast(const scene::Scene& s, glm::vec3 origin) {
  const int n = 400;
  Sides out;
  for (int i = 0; i < n; ++i) {
    float z = 1.0f - (2.0f * float(i) + 1.0f) / float(n);
    float r = std::sqrt(1.0f - z * z);
    float phi = float(i) * 2.39996323f;
    std::optional<Hit> h =
        nearest_hit(s, origin, glm::vec3(r * std::cos(phi), z, r * std::sin(phi)));
    if (!h)
      ++out.miss;
    else if (h->front)
      ++out.front;
    else
      ++out.back;
  }
  return out;
}

// Inside a closed solid every ray hits a back face.
void expect_inside_solid(const scene::Scene& s, glm::vec3 p) {
  Sides c = cast(s, p);
  EXPECT_EQ(c.front + c.miss, 0) << p.x << "," << p.y << "," << p.z;
}

// In a room no ray hits a back face; `open` says whether some may leave through an opening.
void expect_in_room(const scene::Scene& s, glm::vec3 p, bool open) {
  Sides c = cast(s, p);
  EXPECT_EQ(c.back, 0) << p.x << "," << p.y << "," << p.z;
  if (open)
    EXPECT_GT(c.miss, 0);
  else
    EXPECT_EQ(c.miss, 0) << p.x << "," << p.y << "," << p.z;
}

}  // namespace

TEST(BundledScenes, CornellBox) {
  scene::Scene s = bundled("cornell_box.gltf");
  scene::SceneFeatures f = scene::analyze(s);
  EXPECT_EQ(f.instances, 6u);  // one per primitive: 4 room materials, 2 blocks
  EXPECT_EQ(f.punctual_lights(), 0u);
  EXPECT_EQ(f.emissive_materials, 1u);
  EXPECT_FALSE(f.has_environment());
  ASSERT_NE(s.default_camera(), nullptr);
  EXPECT_NEAR(s.default_camera()->forward.z, -1.0f, 1e-5f);
  EXPECT_GT(s.default_camera()->eye.z, 1.0f);  // outside, looking in through the opening
  const scene::Material* light = nullptr;
  for (const auto& m : s.materials)
    if (m.is_emissive()) light = &m;
  ASSERT_NE(light, nullptr);
  EXPECT_FLOAT_EQ(light->emission().r, 15.0f);
  scene::RenderPlan plan = scene::make_plan(f);
  EXPECT_FALSE(plan.direct_lights);
  EXPECT_FALSE(plan.shadow_maps);
  EXPECT_FALSE(plan.specular_probes);
  EXPECT_FALSE(plan.texture_sampling);
  EXPECT_TRUE(plan.emission);
  EXPECT_FALSE(plan.animation);
  // Inside the room (both sides of the light), inside each block.
  expect_in_room(s, {0.0f, 1.0f, 0.5f}, true);
  expect_in_room(s, {0.8f, 1.9f, -0.8f}, true);
  expect_inside_solid(s, {0.33f, 0.3f, 0.28f});
  expect_inside_solid(s, {-0.33f, 0.6f, -0.3f});
}

TEST(BundledScenes, CornellSpot) {
  scene::Scene s = bundled("cornell_spot.gltf");
  scene::SceneFeatures f = scene::analyze(s);
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].type, scene::LightType::Spot);
  EXPECT_NEAR(s.lights[0].direction.y, -1.0f, 1e-5f);
  EXPECT_EQ(f.metal_materials, 1u);
  EXPECT_EQ(f.glossy_materials, 1u);
  EXPECT_EQ(f.emissive_materials, 0u);
  scene::RenderPlan plan = scene::make_plan(f);
  EXPECT_TRUE(plan.specular_probes);
  EXPECT_TRUE(plan.shadow_maps);
  EXPECT_FALSE(plan.point_shadows);
  EXPECT_FALSE(plan.emission);
  expect_in_room(s, {0.0f, 1.0f, 0.5f}, true);
  expect_inside_solid(s, {-0.33f, 0.6f, -0.3f});
}

TEST(BundledScenes, TwoRooms) {
  scene::Scene s = bundled("two_rooms.gltf");
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].type, scene::LightType::Point);
  EXPECT_LT(s.lights[0].position.x, 0.0f);     // in room A only
  EXPECT_GT(s.default_camera()->eye.x, 0.2f);  // looking from room B
  scene::RenderPlan plan = scene::make_plan(scene::analyze(s));
  EXPECT_TRUE(plan.point_shadows);
  expect_in_room(s, {-1.0f, 1.2f, 1.0f}, false);  // room A
  expect_in_room(s, {2.0f, 1.2f, -1.0f}, false);  // room B
  expect_in_room(s, {0.1f, 1.0f, 0.0f}, false);   // in the door
  expect_inside_solid(s, {0.1f, 1.0f, 1.0f});     // inside the wall
  expect_inside_solid(s, {-1.6f, 0.4f, -0.6f});   // inside the crate
}

TEST(BundledScenes, CornellAnimated) {
  scene::Scene s = bundled("cornell_animated.gltf");
  EXPECT_DOUBLE_EQ(s.animation_duration(), 4.0);
  EXPECT_TRUE(scene::make_plan(scene::analyze(s)).animation);
  std::vector<int> moved = s.pose(2.0);
  ASSERT_EQ(moved.size(), 1u);
  EXPECT_NEAR(s.instances[std::size_t(moved[0])].transform[3].x, -0.35f, 1e-6f);
  expect_inside_solid(s, {-0.35f, 0.3f, 0.45f});  // inside the moved block
  EXPECT_EQ(s.pose(4.0).size(), 1u);
  EXPECT_NEAR(s.instances[std::size_t(moved[0])].transform[3].x, 0.33f, 1e-6f);
}

// The dynamic-light scene: a point light on STEP keys that jumps from A to B at 4 s, is switched
// off at 14 s by a move into a closed housing outside the room, and is on again at B at 24 s.
// No instance moves, so pose() reports nothing moved while the light does; the probe grid stays
// on the room although the housing widens the scene's bounds.
TEST(BundledScenes, CornellLight) {
  scene::Scene s = bundled("cornell_light.gltf");
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].type, scene::LightType::Point);
  EXPECT_DOUBLE_EQ(s.animation_duration(), 24.0);
  ASSERT_EQ(s.animations.size(), 1u);
  ASSERT_EQ(s.animations[0].channels.size(), 1u);
  EXPECT_EQ(s.animations[0].channels[0].interpolation, scene::Interpolation::Step);
  scene::RenderPlan plan = scene::make_plan(scene::analyze(s));
  EXPECT_TRUE(plan.animation);
  EXPECT_TRUE(plan.point_shadows);
  EXPECT_TRUE(plan.emission);  // the ceiling quad stays on as a fill light
  ASSERT_TRUE(s.sidecar.probe_bounds.has_value());
  EXPECT_EQ(s.sidecar.probe_bounds->min, glm::vec3(-1.0f, 0.0f, -1.0f));
  EXPECT_EQ(s.sidecar.probe_bounds->max, glm::vec3(1.0f, 2.0f, 1.0f));
  const glm::vec3 a(-0.5f, 1.6f, 0.4f), b(0.5f, 1.6f, -0.5f), housing(0.0f, 1.0f, -1.5f);
  // Frame times at 30 fps as the frame loop computes them (t = k / fps), either side of each key.
  const struct {
    int frame;
    glm::vec3 at;
  } timeline[] = {{0, a}, {119, a}, {120, b}, {419, b}, {420, housing}, {719, housing}, {720, b}, {1019, b}};
  for (const auto& k : timeline) {
    EXPECT_TRUE(s.pose(double(k.frame) / 30.0).empty()) << "frame " << k.frame;
    EXPECT_NEAR(glm::length(s.lights[0].position - k.at), 0.0f, 1e-6f) << "frame " << k.frame;
  }
  // Switched on: the light is in the open room; switched off: every direction meets the housing
  // from inside (back faces), so no light reaches the room.
  expect_in_room(s, a, true);
  expect_in_room(s, b, true);
  expect_inside_solid(s, housing);
  expect_inside_solid(s, housing + glm::vec3(0.15f, -0.15f, 0.1f));
}
