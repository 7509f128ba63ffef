// Animation sampling with hand-computed values, and Scene::pose.
#include <gtest/gtest.h>

#include <cmath>

#include "gltf_builder.h"
#include "scene/gltf_loader.h"

using namespace ddish;
using scene::AnimChannel;
using scene::AnimPath;
using scene::Interpolation;

namespace {

// Keyframe values as AnimChannel stores them: `width` floats of each vector.
std::vector<float> flat(const std::vector<glm::vec4>& values, int width) {
  std::vector<float> out;
  for (const glm::vec4& v : values)
    for (int i = 0; i < width; ++i) out.push_back(v[i]);
  return out;
}

AnimChannel translation(Interpolation interp, std::vector<float> times,
                        std::vector<glm::vec4> values) {
  AnimChannel c;
  c.path = AnimPath::Translation;
  c.interpolation = interp;
  c.times = std::move(times);
  c.width = 3;
  c.values = flat(values, 3);
  return c;
}

}  // namespace

TEST(Animation, StepHoldsThePreviousKey) {
  AnimChannel c =
      translation(Interpolation::Step, {1, 2, 4}, {{0, 0, 0, 0}, {10, 0, 0, 0}, {20, 0, 0, 0}});
  EXPECT_FLOAT_EQ(c.sample(0.0f).x, 0.0f);  // before the first key: clamped
  EXPECT_FLOAT_EQ(c.sample(1.99f).x, 0.0f);
  EXPECT_FLOAT_EQ(c.sample(2.0f).x, 10.0f);
  EXPECT_FLOAT_EQ(c.sample(3.9f).x, 10.0f);
  EXPECT_FLOAT_EQ(c.sample(9.0f).x, 20.0f);  // after the last key: clamped
}

TEST(Animation, LinearInterpolates) {
  AnimChannel c =
      translation(Interpolation::Linear, {0, 2, 3}, {{0, 0, 0, 0}, {4, -2, 8, 0}, {5, 0, 0, 0}});
  glm::vec4 v = c.sample(0.5f);  // a quarter of the way from key 0 to key 1
  EXPECT_FLOAT_EQ(v.x, 1.0f);
  EXPECT_FLOAT_EQ(v.y, -0.5f);
  EXPECT_FLOAT_EQ(v.z, 2.0f);
  EXPECT_FLOAT_EQ(c.sample(2.5f).x, 4.5f);
}

TEST(Animation, LinearRotationIsSlerp) {
  AnimChannel c;
  c.path = AnimPath::Rotation;
  c.times = {0, 1};
  float s = std::sqrt(0.5f);
  c.width = 4;
  c.values = flat({{0, 0, 0, 1}, {0, s, 0, s}}, 4);  // identity to 90 degrees about Y
  glm::vec4 q = c.sample(0.5f);             // 45 degrees: (0, sin 22.5, 0, cos 22.5)
  EXPECT_NEAR(q.y, std::sin(0.3926991f), 1e-6f);
  EXPECT_NEAR(q.w, std::cos(0.3926991f), 1e-6f);
  q = c.sample(0.25f);  // 22.5 degrees; a normalised lerp would give 0.2022 instead of 0.1951
  EXPECT_NEAR(q.y, std::sin(0.19634954f), 1e-6f);
  // The shorter arc: the same rotation stored with opposite sign interpolates identically.
  for (int i = 4; i < 8; ++i) c.values[std::size_t(i)] = -c.values[std::size_t(i)];
  EXPECT_NEAR(std::abs(c.sample(0.5f).y), std::sin(0.3926991f), 1e-6f);
}

TEST(Animation, CubicSplineUsesScaledTangents) {
  // Keys at t = 1 and t = 3 (interval 2): values 0 and 1, out-tangent of key 0 = 1, in-tangent of
  // key 1 = 2. At s = 0.5: h00 = 0.5, h10 = 0.125, h01 = 0.5, h11 = -0.125, so
  // p = 0.5*0 + 2*0.125*1 + 0.5*1 + 2*(-0.125)*2 = 0.25.
  AnimChannel c = translation(Interpolation::CubicSpline, {1, 3},
                              {{9, 0, 0, 0},
                               {0, 0, 0, 0},
                               {1, 0, 0, 0},  // in, value, out
                               {2, 0, 0, 0},
                               {1, 0, 0, 0},
                               {9, 0, 0, 0}});
  EXPECT_FLOAT_EQ(c.sample(2.0f).x, 0.25f);
  // s = 0.25: h00 = 0.84375, h10 = 0.140625, h01 = 0.15625, h11 = -0.046875:
  // p = 2*0.140625 + 0.15625 - 2*0.046875*2 = 0.25.
  EXPECT_FLOAT_EQ(c.sample(1.5f).x, 0.25f);
  EXPECT_FLOAT_EQ(c.sample(0.0f).x, 0.0f);  // the value, not the in-tangent
  EXPECT_FLOAT_EQ(c.sample(5.0f).x, 1.0f);
}

// A "weights" channel is as wide as the mesh has targets (here 5, more than a vec4 holds).
TEST(Animation, WeightsChannelSamplesEveryTarget) {
  AnimChannel c;
  c.path = AnimPath::Weights;
  c.width = 5;
  c.times = {0, 2};
  c.values = {0, 1, 2, 3, 4, 4, 3, 2, 1, 0};
  float w[5];
  c.sample(0.5f, w);  // a quarter of the way
  const float want[5] = {1.0f, 1.5f, 2.0f, 2.5f, 3.0f};
  for (int i = 0; i < 5; ++i) EXPECT_FLOAT_EQ(w[i], want[i]) << i;
  c.interpolation = Interpolation::Step;
  c.sample(1.9f, w);
  for (int i = 0; i < 5; ++i) EXPECT_FLOAT_EQ(w[i], float(i)) << i;
  c.sample(3.0f, w);  // clamped at the last key
  for (int i = 0; i < 5; ++i) EXPECT_FLOAT_EQ(w[i], float(4 - i)) << i;
}

TEST(Animation, Duration) {
  scene::Animation a;
  a.channels.push_back(translation(Interpolation::Linear, {0, 2}, {{0, 0, 0, 0}, {1, 0, 0, 0}}));
  a.channels.push_back(translation(Interpolation::Linear, {1, 3.5f}, {{0, 0, 0, 0}, {1, 0, 0, 0}}));
  EXPECT_FLOAT_EQ(a.duration(), 3.5f);
}

// A parent node animated along +X carries its child; a second, static instance never moves.
TEST(Animation, PoseMovesAnimatedInstancesLightsAndCameras) {
  test::TempDir dir("pose");
  test::GltfBuilder b;
  int mesh = b.add_quad_mesh();
  b.doc["extensions"]["KHR_lights_punctual"]["lights"] = {{{"type", "point"}, {"intensity", 5}}};
  b.doc["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.7}, {"znear", 0.05}}}}};
  b.add_node({{"name", "mover"}, {"children", {1, 2, 3}}});
  b.add_node({{"name", "child"}, {"translation", {0, 1, 0}}, {"mesh", mesh}});
  b.add_node({{"name", "lamp"}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  b.add_node({{"name", "cam"}, {"camera", 0}});
  b.add_node({{"name", "static"}, {"mesh", mesh}});
  int in = b.add_floats({0, 2}, "SCALAR", 2);
  int out = b.add_floats({0, 0, 0, 4, 0, 0}, "VEC3", 2);
  nlohmann::json sampler = {{"input", in}, {"output", out}, {"interpolation", "LINEAR"}};
  nlohmann::json target = {{"node", 0}, {"path", "translation"}};
  nlohmann::json channel = {{"sampler", 0}, {"target", target}};
  nlohmann::json anim = {{"name", "slide"}};
  anim["samplers"].push_back(sampler);
  anim["channels"].push_back(channel);
  b.doc["animations"].push_back(anim);
  scene::Scene s =
      scene::load_scene(b.write(dir.path.string(), "p.gltf", test::BufferMode::External));
  ASSERT_EQ(s.instances.size(), 2u);
  EXPECT_DOUBLE_EQ(s.animation_duration(), 2.0);
  int child = s.instances[0].node == 1 ? 0 : 1;

  std::vector<int> moved = s.pose(0.5);
  ASSERT_EQ(moved.size(), 1u);
  EXPECT_EQ(moved[0], child);
  EXPECT_FLOAT_EQ(s.instances[std::size_t(child)].transform[3].x, 1.0f);
  EXPECT_FLOAT_EQ(s.instances[std::size_t(child)].transform[3].y, 1.0f);
  EXPECT_FLOAT_EQ(s.lights[0].position.x, 1.0f);
  EXPECT_FLOAT_EQ(s.cameras[0].eye.x, 1.0f);
  EXPECT_DOUBLE_EQ(s.time, 0.5);

  EXPECT_TRUE(s.pose(0.5).empty());  // nothing moves when the time does not change
  EXPECT_EQ(s.pose(5.0).size(), 1u);
  EXPECT_FLOAT_EQ(s.lights[0].position.x, 4.0f);  // clamped at the last key
  EXPECT_TRUE(s.pose(7.0).empty());
}
