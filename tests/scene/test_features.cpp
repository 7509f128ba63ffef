// SceneFeatures counts and the plan derived from them.
#include <gtest/gtest.h>

#include <algorithm>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/features.h"

using namespace ddish;

namespace {

scene::Mesh triangle(int material) {
  scene::Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.indices = {0, 1, 2};
  m.material = material;
  m.bounds.expand(glm::vec3(0.0f));
  m.bounds.expand(glm::vec3(1.0f, 1.0f, 0.0f));
  return m;
}

bool left_out(const scene::RenderPlan& p, const std::string& what) {
  return std::any_of(p.left_out.begin(), p.left_out.end(),
                     [&](const scene::PlanItem& i) { return i.what == what && !i.why.empty(); });
}

}  // namespace

TEST(Features, MatteUntexturedStaticSceneLeavesOutEverythingOptional) {
  scene::Scene s;
  scene::Material matte;
  matte.metallic = 0.0f;
  matte.roughness = 0.9f;
  scene::Material unused;  // glossy, textured, emissive, but drawn by nothing
  unused.roughness = 0.1f;
  unused.emissive = glm::vec3(1.0f);
  unused.base_color_texture.texture = 0;
  s.materials = {matte, unused};
  s.textures.resize(1);
  s.meshes = {triangle(0)};
  s.nodes.resize(1);
  s.instances = {{0, 0, glm::mat4(1.0f)},
                 {0, 0, glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, 2))}};

  scene::SceneFeatures f = scene::analyze(s);
  EXPECT_EQ(f.triangles, 2u);
  EXPECT_EQ(f.instances, 2u);
  EXPECT_EQ(f.materials_used, 1u);
  EXPECT_EQ(f.glossy_materials, 0u);
  EXPECT_EQ(f.textures_used, 0u);
  EXPECT_FLOAT_EQ(f.bounds.max.z, 2.0f);

  scene::RenderPlan p = scene::make_plan(f);
  for (bool flag :
       {p.direct_lights, p.shadow_maps, p.point_shadows, p.specular_probes, p.texture_sampling,
        p.normal_mapping, p.alpha_test, p.alpha_blend, p.emission, p.environment, p.animation})
    EXPECT_FALSE(flag);
  EXPECT_EQ(p.left_out.size(), 11u);
  EXPECT_TRUE(left_out(p, "shadow maps"));
  EXPECT_TRUE(left_out(p, "specular probe term"));
  EXPECT_TRUE(left_out(p, "texture sampling"));
}

TEST(Features, WhatTheSceneHoldsIsKept) {
  scene::Scene s;
  scene::Material a;  // the glTF default is metallic 1: a metal
  a.alpha_mode = scene::AlphaMode::Mask;
  a.normal_texture.texture = 0;
  scene::Material b;
  b.metallic = 0.0f;
  b.roughness = 0.3f;  // glossy
  b.emissive = glm::vec3(0.5f);
  b.alpha_mode = scene::AlphaMode::Blend;
  s.materials = {a, b};
  s.textures.resize(1);
  s.meshes = {triangle(0), triangle(1), triangle(-1)};
  s.nodes.resize(1);
  s.instances = {{0, 0, glm::mat4(1.0f)}, {1, 0, glm::mat4(1.0f)}, {2, 0, glm::mat4(1.0f)}};
  s.lights.resize(2);
  s.lights[0].type = scene::LightType::Spot;
  s.lights[1].type = scene::LightType::Point;
  s.sidecar.environment = glm::vec3(0.1f);
  s.animations.resize(1);

  scene::SceneFeatures f = scene::analyze(s);
  EXPECT_EQ(f.materials_used, 3u);  // a, b and the default material
  EXPECT_EQ(f.metal_materials, 2u);
  EXPECT_EQ(f.glossy_materials, 1u);
  EXPECT_EQ(f.normal_mapped_materials, 1u);
  EXPECT_EQ(f.masked_materials, 1u);
  EXPECT_EQ(f.blended_materials, 1u);
  EXPECT_EQ(f.emissive_materials, 1u);
  EXPECT_EQ(f.spot_lights, 1u);
  EXPECT_EQ(f.point_lights, 1u);
  scene::RenderPlan p = scene::make_plan(f);
  EXPECT_TRUE(p.left_out.empty());
  EXPECT_TRUE(p.shadow_maps && p.point_shadows && p.specular_probes && p.texture_sampling &&
              p.normal_mapping && p.alpha_test && p.alpha_blend && p.emission && p.environment &&
              p.animation && p.direct_lights);
}

TEST(Features, PointLightsOnlyNeedNoPlanarShadowMaps) {
  scene::SceneFeatures f;
  f.point_lights = 1;
  scene::RenderPlan p = scene::make_plan(f);
  EXPECT_TRUE(p.direct_lights);
  EXPECT_TRUE(p.point_shadows);
  EXPECT_FALSE(p.shadow_maps);
}
