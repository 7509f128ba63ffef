#include "app/lighting_options.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "metrics/image_io.h"
#include "scene/environment_choice.h"
#include "scene/environment_map.h"
#include "scene/sidecar.h"
#include "scene/scene.h"

namespace ddish::app {

void add_lighting_options(CLI::App& cmd, LightingArgs& args, bool exposure) {
  CLI::Option* sky = cmd.add_option(
      "--sky", args.sky,
      "uniform sky radiance R,G,B (0,0,0: none; default: the sidecar's, else a neutral sky of "
      "radiance 1 when the scene has no light, else none)");
  cmd.add_option("--environment", args.environment,
                 "image-based lighting: an equirectangular HDR map FILE.exr|.hdr (twice as wide as "
                 "high; linear radiance; row 0 up (+Y), the centre column toward -Z, +X to its "
                 "right) in place of any uniform sky; importance-sampled by the path tracer, "
                 "carried by the probes, drawn as the background")
      ->excludes(sky);
  cmd.add_option("--environment-rotation", args.environment_rotation_deg,
                 "turns --environment about the up axis (+Y) by DEG degrees, counter-clockwise "
                 "seen from above")
      ->capture_default_str();
  cmd.add_option("--environment-intensity", args.environment_intensity,
                 "multiplies --environment's radiance by K")
      ->capture_default_str()
      ->check(CLI::Range(0.0f, 1e30f));
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

namespace {

void check_environment_file(const std::string& file) {
  std::string ext = std::filesystem::path(file).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext != ".exr" && ext != ".hdr")
    throw std::invalid_argument("--environment wants an .exr or .hdr file, got '" + file + "'");
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
    throw std::invalid_argument("--environment: cannot read " + file + ": no such file");
}

}  // namespace

std::optional<glm::vec3> sky_radiance(const LightingArgs& args) {
  if (!args.environment.empty()) check_environment_file(args.environment);
  if (!std::isfinite(args.environment_rotation_deg))
    throw std::invalid_argument("--environment-rotation must be a finite angle in degrees");
  if (args.sky.empty()) return std::nullopt;
  return parse_sky(args.sky);
}

namespace {

// `what` names where the file was asked for in the error: "--environment" or the sidecar.
std::shared_ptr<const scene::EnvironmentMap> read_environment(const std::string& file, float rotation_deg,
                                                              float intensity, const std::string& what) {
  metrics::Image image;
  try {
    image = metrics::read_image(file);
  } catch (const std::exception& e) {
    throw std::runtime_error(what + ": " + e.what());
  }
  const int w = image.width();
  const int h = image.height();
  return std::make_shared<const scene::EnvironmentMap>(
      scene::make_environment_map(w, h, std::move(image.pixels()), rotation_deg, intensity, file));
}

}  // namespace

std::shared_ptr<const scene::EnvironmentMap> load_environment(const LightingArgs& args) {
  if (args.environment.empty()) return nullptr;
  check_environment_file(args.environment);
  return read_environment(args.environment, args.environment_rotation_deg, args.environment_intensity,
                          "--environment");
}

float exposure_scale(const LightingArgs& args) { return std::exp2(args.exposure_ev); }

std::string apply_lighting(scene::Scene& s, const LightingArgs& args) {
  // --environment, else --sky, else the sidecar's map, else the uniform choices.
  std::shared_ptr<const scene::EnvironmentMap> map = load_environment(args);
  float rotation_deg = args.environment_rotation_deg;
  const char* source = "--environment";
  if (!map && args.sky.empty() && s.sidecar.environment_map) {
    const scene::SidecarEnvironmentMap& m = *s.sidecar.environment_map;
    map = read_environment(m.file, m.rotation_deg, m.intensity, scene::sidecar_path(s.path) + ": environment.map");
    rotation_deg = m.rotation_deg;
    source = "sidecar";
  }
  if (map) {
    const std::string line = fmt::format("environment map {} ({}x{}, rotation {:g} deg, intensity {:g}): {}",
                                         map->source, map->width, map->height, rotation_deg,
                                         map->intensity, source);
    scene::apply_environment(s, std::nullopt, std::move(map));
    return line;
  }
  const scene::EnvironmentChoice c = scene::apply_environment(s, sky_radiance(args));
  return fmt::format("environment ({:g}, {:g}, {:g}) radiance: {}", c.radiance.r, c.radiance.g,
                     c.radiance.b, scene::environment_source_name(c.source));
}

}  // namespace ddish::app
