// Which uniform environment (sky) radiance a scene is rendered with. Most glTF models carry no
// light at all (no KHR_lights_punctual light, no emissive surface) and rendered black; like glTF
// viewers, ddish then lights them with a neutral default sky. The command line (--sky) and the
// sidecar's environment.radiance, in that order, win over the default, and 0 switches it off.
// An environment map (--environment, scene/environment_map.h) wins over all of them.
#pragma once

#include <memory>
#include <optional>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace ddish::scene {

// Radiance of the default sky, the same in every direction and channel. Under it, an unshadowed
// white Lambertian surface reflects radiance 1 whichever way it faces (irradiance pi, times
// albedo / pi), the brightest a non-emissive surface can be: display white before the tone
// curve, which keeps highlights off the clip.
inline constexpr float kDefaultSkyRadiance = 1.0f;

enum class EnvironmentSource { Map, CommandLine, SidecarMap, Sidecar, DefaultSky, None };

struct EnvironmentChoice {
  glm::vec3 radiance{0.0f};  // the uniform radiance (0 with a map)
  EnvironmentSource source = EnvironmentSource::None;
};

// Whether the scene has a light of its own: a punctual light, or an emissive material that an
// instance draws.
bool has_own_light(const Scene& scene);

// sky if given, else the sidecar's environment.map (radiance 0: the caller loads the map, which
// scene/ cannot read), else its environment.radiance, else the default sky when the scene has no
// light of its own, else none (radiance 0).
EnvironmentChoice choose_environment(const Scene& scene, const std::optional<glm::vec3>& sky);

// choose_environment's radiance made the scene's environment (what every renderer reads); a
// map, when given, replaces the uniform radiance (which becomes 0).
EnvironmentChoice apply_environment(Scene& scene, const std::optional<glm::vec3>& sky,
                                    std::shared_ptr<const EnvironmentMap> map = nullptr);

// "--environment", "--sky", "sidecar map", "sidecar", "default sky (the scene has no light)", "none".
const char* environment_source_name(EnvironmentSource source);

}  // namespace ddish::scene
