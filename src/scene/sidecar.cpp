#include "scene/sidecar.h"

#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "scene/load_error.h"

namespace ddish::scene {

namespace {

using nlohmann::json;

glm::vec3 vec3_of(const json& j, const std::string& what, const std::string& file) {
  if (!j.is_array() || j.size() != 3)
    throw LoadError(file, what + " must be an array of 3 numbers");
  glm::vec3 v;
  for (int i = 0; i < 3; ++i) {
    const json& e = j[std::size_t(i)];
    // A number beyond float's range (1e39, or 1e400 that the parser reads as infinity) would
    // become Inf once narrowed: check the float that is kept, not the double that was read.
    if (!e.is_number() || !std::isfinite(e.get<double>()) || !std::isfinite(e.get<float>()))
      throw LoadError(file, what + " must be an array of 3 finite numbers");
    v[i] = e.get<float>();
  }
  return v;
}

const json& object_member(const json& j, const char* key, const std::string& file) {
  const json& m = j.at(key);
  if (!m.is_object()) throw LoadError(file, std::string("\"") + key + "\" must be an object");
  return m;
}

// environment.map (a path relative to the sidecar), .rotation (degrees) and .intensity.
SidecarEnvironmentMap environment_map_of(const json& env, const std::string& file) {
  if (!env["map"].is_string() || env["map"].get<std::string>().empty())
    throw LoadError(file, "environment.map must be the name of an .exr or .hdr file");
  SidecarEnvironmentMap m;
  const std::filesystem::path name = env["map"].get<std::string>();
  m.file = (std::filesystem::path(file).parent_path() / name).lexically_normal().string();
  std::string ext = name.extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".exr" && ext != ".hdr")
    throw LoadError(file, "environment.map must be an .exr or .hdr file, got '" + name.string() + "'");
  std::error_code ec;
  if (!std::filesystem::is_regular_file(m.file, ec))
    throw LoadError(file, "environment.map: cannot read " + m.file + ": no such file");
  const auto number = [&](const char* key, float& out) {
    if (!env.contains(key)) return;
    const json& v = env[key];
    if (!v.is_number() || !std::isfinite(v.get<double>()) || !std::isfinite(v.get<float>()))
      throw LoadError(file, std::string("environment.") + key + " must be a finite number");
    out = v.get<float>();
  };
  number("rotation", m.rotation_deg);
  number("intensity", m.intensity);
  if (m.intensity < 0.0f) throw LoadError(file, "environment.intensity must not be negative");
  return m;
}

}  // namespace

std::string sidecar_path(const std::string& scene_path) {
  std::filesystem::path p(scene_path);
  return (p.parent_path() / (p.stem().string() + ".ddish.json")).string();
}

Sidecar parse_sidecar(const std::string& text, const std::string& file) {
  json j = json::parse(text, nullptr, /*allow_exceptions=*/false, /*ignore_comments=*/true);
  if (j.is_discarded()) throw LoadError(file, "not valid JSON");
  if (!j.is_object()) throw LoadError(file, "the sidecar must be a JSON object");
  Sidecar sc;
  if (j.contains("environment")) {
    const json& env = object_member(j, "environment", file);
    if (env.contains("radiance")) {
      sc.environment = vec3_of(env["radiance"], "environment.radiance", file);
      sc.environment_given = true;
      if (glm::any(glm::lessThan(sc.environment, glm::vec3(0.0f))))
        throw LoadError(file, "environment.radiance must not be negative");
    }
    if (env.contains("map")) {
      if (sc.environment_given)
        throw LoadError(file, "environment has both a radiance and a map: give one");
      sc.environment_map = environment_map_of(env, file);
    } else if (env.contains("rotation") || env.contains("intensity")) {
      throw LoadError(file, "environment.rotation and environment.intensity need an environment.map");
    }
  }
  if (j.contains("probe_grid")) {
    const json& grid = object_member(j, "probe_grid", file);
    if (grid.contains("counts")) {
      const json& c = grid["counts"];
      if (!c.is_array() || c.size() != 3)
        throw LoadError(file, "probe_grid.counts must be an array of 3 integers");
      glm::ivec3 counts;
      for (int i = 0; i < 3; ++i) {
        const json& e = c[std::size_t(i)];
        if (!e.is_number_integer() || e.get<long long>() < 1 || e.get<long long>() > 4096)
          throw LoadError(file, "probe_grid.counts must be 3 integers between 1 and 4096");
        counts[i] = e.get<int>();
      }
      sc.probe_counts = counts;
    }
    if (grid.contains("bounds")) {
      const json& b = object_member(grid, "bounds", file);
      if (!b.contains("min") || !b.contains("max"))
        throw LoadError(file, "probe_grid.bounds needs \"min\" and \"max\"");
      Aabb box;
      box.min = vec3_of(b["min"], "probe_grid.bounds.min", file);
      box.max = vec3_of(b["max"], "probe_grid.bounds.max", file);
      if (!glm::all(glm::lessThan(box.min, box.max)))
        throw LoadError(file, "probe_grid.bounds.min must be below max on every axis");
      sc.probe_bounds = box;
    }
  }
  if (j.contains("light_units")) {
    const json& u = j["light_units"];
    if (u == "radiometric")
      sc.light_units = LightUnits::Radiometric;
    else if (u == "photometric")
      sc.light_units = LightUnits::Photometric;
    else
      throw LoadError(file, "\"light_units\" must be \"photometric\" or \"radiometric\"");
  }
  if (j.contains("camera")) {
    if (!j["camera"].is_string()) throw LoadError(file, "\"camera\" must be a string");
    sc.camera = j["camera"].get<std::string>();
  }
  return sc;
}

Sidecar load_sidecar(const std::string& scene_path) {
  std::string file = sidecar_path(scene_path);
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) return Sidecar{};
  std::ifstream in(file, std::ios::binary);
  if (!in) throw LoadError(file, "cannot be read");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_sidecar(text.str(), file);
}

}  // namespace ddish::scene
