#include "scene/environment_choice.h"

#include "scene/features.h"

namespace ddish::scene {

bool has_own_light(const Scene& scene) {
  const SceneFeatures f = analyze(scene);
  return f.punctual_lights() > 0 || f.emissive_materials > 0;
}

EnvironmentChoice choose_environment(const Scene& scene, const std::optional<glm::vec3>& sky) {
  if (sky) return {*sky, EnvironmentSource::CommandLine};
  if (scene.sidecar.environment_map) return {glm::vec3(0.0f), EnvironmentSource::SidecarMap};
  if (scene.sidecar.environment_given) return {scene.sidecar.environment, EnvironmentSource::Sidecar};
  if (!has_own_light(scene)) return {glm::vec3(kDefaultSkyRadiance), EnvironmentSource::DefaultSky};
  return {glm::vec3(0.0f), EnvironmentSource::None};
}

EnvironmentChoice apply_environment(Scene& scene, const std::optional<glm::vec3>& sky,
                                    std::shared_ptr<const EnvironmentMap> map) {
  const EnvironmentChoice c =
      map ? EnvironmentChoice{glm::vec3(0.0f), EnvironmentSource::Map} : choose_environment(scene, sky);
  scene.sidecar.environment = c.radiance;
  scene.environment_map = std::move(map);
  return c;
}

const char* environment_source_name(EnvironmentSource source) {
  switch (source) {
    case EnvironmentSource::Map:
      return "--environment";
    case EnvironmentSource::CommandLine:
      return "--sky";
    case EnvironmentSource::SidecarMap:
      return "sidecar map";
    case EnvironmentSource::Sidecar:
      return "sidecar";
    case EnvironmentSource::DefaultSky:
      return "default sky (the scene has no light)";
    case EnvironmentSource::None:
      return "none";
  }
  return "?";
}

}  // namespace ddish::scene
