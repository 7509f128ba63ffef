// glTF light units (photometric unless the sidecar says "light_units": "radiometric") and the
// environment a scene is rendered with (scene/environment_choice.h).
#include <gtest/gtest.h>

#include <string>

#include "scene/environment_choice.h"
#include "scene/gltf_loader.h"
#include "scene/load_error.h"
#include "scene/sidecar.h"

using namespace ddish;

namespace {

scene::Scene bundled(const char* name) {
  return scene::load_scene(std::string(DDISH_SOURCE_DIR) + "/scenes/" + name);
}

}  // namespace

TEST(LightUnits, PhotometricFileIsConvertedAt683LumensPerWatt) {
  // photometric_lamp has no sidecar: its point light's 683 cd are 1 W/sr.
  const scene::Scene s = bundled("photometric_lamp.gltf");
  EXPECT_EQ(s.sidecar.light_units, scene::LightUnits::Photometric);
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_FLOAT_EQ(s.lights[0].intensity, 1.0f);
}

TEST(LightUnits, RadiometricSidecarKeepsTheNumbers) {
  // cornell_spot's sidecar declares radiometric units: the file's 25 stays 25 W/sr.
  const scene::Scene s = bundled("cornell_spot.gltf");
  EXPECT_EQ(s.sidecar.light_units, scene::LightUnits::Radiometric);
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_FLOAT_EQ(s.lights[0].intensity, 25.0f);
  for (const char* name : {"cornell_box.gltf", "cornell_animated.gltf", "cornell_light.gltf",
                           "two_rooms.gltf"})
    EXPECT_EQ(bundled(name).sidecar.light_units, scene::LightUnits::Radiometric) << name;
}

TEST(LightUnits, SidecarKeyIsChecked) {
  EXPECT_EQ(scene::parse_sidecar(R"({"light_units": "photometric"})", "x").light_units,
            scene::LightUnits::Photometric);
  EXPECT_EQ(scene::parse_sidecar(R"({"light_units": "radiometric"})", "x").light_units,
            scene::LightUnits::Radiometric);
  EXPECT_EQ(scene::parse_sidecar("{}", "x").light_units, scene::LightUnits::Photometric);
  EXPECT_THROW(scene::parse_sidecar(R"({"light_units": "watts"})", "x"), scene::LoadError);
  EXPECT_THROW(scene::parse_sidecar(R"({"light_units": 1})", "x"), scene::LoadError);
}

TEST(Environment, SceneWithoutLightGetsTheDefaultSky) {
  const scene::Scene s = bundled("open_sphere.gltf");
  EXPECT_FALSE(scene::has_own_light(s));
  const scene::EnvironmentChoice c = scene::choose_environment(s, std::nullopt);
  EXPECT_EQ(c.source, scene::EnvironmentSource::DefaultSky);
  EXPECT_EQ(c.radiance, glm::vec3(scene::kDefaultSkyRadiance));
}

TEST(Environment, CommandLineBeatsSidecarBeatsDefault) {
  scene::Scene s = bundled("open_sphere.gltf");
  scene::EnvironmentChoice c = scene::choose_environment(s, glm::vec3(0.0f));
  EXPECT_EQ(c.source, scene::EnvironmentSource::CommandLine);  // --sky 0,0,0 switches it off
  EXPECT_EQ(c.radiance, glm::vec3(0.0f));
  s.sidecar.environment = glm::vec3(0.2f);
  s.sidecar.environment_given = true;
  EXPECT_EQ(scene::choose_environment(s, std::nullopt).source, scene::EnvironmentSource::Sidecar);
  EXPECT_EQ(scene::choose_environment(s, glm::vec3(3.0f)).radiance, glm::vec3(3.0f));
  c = scene::apply_environment(s, glm::vec3(0.5f, 0.6f, 0.7f));
  EXPECT_EQ(s.environment(), glm::vec3(0.5f, 0.6f, 0.7f));
}

TEST(Environment, LitScenesKeepTheirOwn) {
  // cornell_box: the sidecar's explicit 0 (and its emissive ceiling); photometric_lamp: no
  // sidecar but a point light, so no sky is added.
  EXPECT_EQ(scene::choose_environment(bundled("cornell_box.gltf"), std::nullopt).source,
            scene::EnvironmentSource::Sidecar);
  const scene::Scene lamp = bundled("photometric_lamp.gltf");
  EXPECT_TRUE(scene::has_own_light(lamp));
  const scene::EnvironmentChoice c = scene::choose_environment(lamp, std::nullopt);
  EXPECT_EQ(c.source, scene::EnvironmentSource::None);
  EXPECT_EQ(c.radiance, glm::vec3(0.0f));
}
