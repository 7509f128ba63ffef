#include "app/lighting_options.h"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "scene/environment_choice.h"
#include "scene/scene.h"

namespace ddish::app {

void add_lighting_options(CLI::App& cmd, LightingArgs& args, bool exposure) {
  cmd.add_option(
      "--sky", args.sky,
      "uniform sky radiance R,G,B (0,0,0: none; default: the sidecar's, else a neutral sky of "
      "radiance 1 when the scene has no light, else none)");
  if (exposure)
    cmd.add_option("--exposure", args.exposure_ev,
                   "exposure in stops: display values are scaled by 2^EV before the tone curve "
                   "(the EXR stays linear)")
        ->capture_default_str()
        ->check(CLI::Range(-64.0f, 64.0f));
}

glm::vec3 parse_sky(const std::string& text) {
  std::vector<float> v;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    std::size_t used = 0;
    float f = -1.0f;
    try {
      f = std::stof(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != item.size() || !std::isfinite(f) || f < 0.0f)
      throw std::invalid_argument("--sky: '" + item +
                                  "' is not a radiance (want R,G,B, three numbers >= 0)");
    v.push_back(f);
  }
  if (v.size() != 3 || text.empty() || text.back() == ',')
    throw std::invalid_argument("--sky wants three numbers R,G,B, got '" + text + "'");
  return {v[0], v[1], v[2]};
}

std::optional<glm::vec3> sky_radiance(const LightingArgs& args) {
  if (args.sky.empty()) return std::nullopt;
  return parse_sky(args.sky);
}

float exposure_scale(const LightingArgs& args) { return std::exp2(args.exposure_ev); }

std::string apply_lighting(scene::Scene& s, const LightingArgs& args) {
  const scene::EnvironmentChoice c = scene::apply_environment(s, sky_radiance(args));
  return fmt::format("environment ({:g}, {:g}, {:g}) radiance: {}", c.radiance.r, c.radiance.g,
                     c.radiance.b, scene::environment_source_name(c.source));
}

}  // namespace ddish::app
