// The lighting and display options that `ddish render`, `ddish reference` and `ddish probes`
// share: --sky R,G,B (the uniform environment radiance, over the sidecar's and the default sky,
// scene/environment_choice.h), --environment FILE.exr|.hdr with --environment-rotation DEG and
// --environment-intensity K (an equirectangular map in place of any uniform sky,
// scene/environment_map.h) and, for the commands that write display images, --exposure EV.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include <glm/glm.hpp>

namespace CLI {
class App;
}

namespace ddish::scene {
struct Scene;
struct EnvironmentMap;
}  // namespace ddish::scene

namespace ddish::app {

struct LightingArgs {
  std::string sky;           // --sky R,G,B as given; empty: not given
  std::string environment;   // --environment FILE; empty: not given
  float environment_rotation_deg = 0.0f;  // --environment-rotation DEG, about +Y
  float environment_intensity = 1.0f;     // --environment-intensity K, multiplies the texels
  float exposure_ev = 0.0f;      // --exposure EV: display values are scaled by 2^EV
};

// Registers --sky and the --environment options, and --exposure when `exposure` is true.
void add_lighting_options(CLI::App& cmd, LightingArgs& args, bool exposure);

// "R,G,B" -> three finite radiances >= 0; throws std::invalid_argument naming --sky otherwise.
glm::vec3 parse_sky(const std::string& text);

// --sky's radiance, nothing when it is not given; throws std::invalid_argument when it is
// malformed, or when --environment names no readable .exr or .hdr file (commands call it before
// loading the scene, so a typo costs no load).
std::optional<glm::vec3> sky_radiance(const LightingArgs& args);

// Reads --environment's file (OpenImageIO) into a map with the rotation and intensity; nothing
// when it is not given. Throws with one line naming the file when it is unreadable, not twice
// as wide as high, or holds negative or non-finite values.
std::shared_ptr<const scene::EnvironmentMap> load_environment(const LightingArgs& args);

// The display scale 2^EV of --exposure.
float exposure_scale(const LightingArgs& args);

// Makes the scene's environment the one the options and the scene choose, and returns the
// run-log line that says which: "environment (r, g, b) radiance: default sky (...)", or
// "environment map FILE (WxH, rotation D deg, intensity K): --environment".
std::string apply_lighting(scene::Scene& scene, const LightingArgs& args);

}  // namespace ddish::app
