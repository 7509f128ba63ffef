// `ddish info SCENE`: what a scene holds and what the renderer will leave out for it.
#include <algorithm>
#include <chrono>
#include <memory>
#include <string>

#include <fmt/format.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "app/camera_options.h"
#include "app/commands.h"
#include "app/plan_report.h"
#include "app/probe_options.h"
#include "app/probe_setup.h"
#include "app/tracer_choice.h"
#include "probes/surface_cells.h"
#include "scene/environment_choice.h"
#include "scene/features.h"
#include "scene/framing.h"
#include "scene/gltf_loader.h"

namespace ddish::app {

namespace {

struct InfoOptions {
  std::string scene;
  bool json = false;
  bool decode = false;
};

const char* light_type(scene::LightType t) {
  switch (t) {
    case scene::LightType::Directional:
      return "directional";
    case scene::LightType::Point:
      return "point";
    case scene::LightType::Spot:
      return "spot";
  }
  return "?";
}

nlohmann::json vec(const glm::vec3& v) { return {v.x, v.y, v.z}; }

// The camera render and reference use without --camera: the scene's default camera, else the
// framing camera (for the default square view and field of view; a portrait view is framed
// by its narrower horizontal field).
scene::Camera view_camera(const scene::Scene& s) {
  if (const scene::Camera* c = s.default_camera()) return *c;
  return scene::framing_camera(scene::bounding_sphere(s), glm::radians(kDefaultFovDeg), 1.0f);
}

const char* light_units(const scene::Scene& s) {
  return s.sidecar.light_units == scene::LightUnits::Radiometric
             ? "radiometric (sidecar): W/sr, W/m^2"
             : "photometric (glTF): candela, lux; / 683 lm/W";
}

nlohmann::json to_json(const scene::Scene& s, const scene::SceneFeatures& f,
                       const scene::RenderPlan& plan, const scene::EnvironmentChoice& env,
                       double seconds, const std::string& tracer) {
  using nlohmann::json;
  json j;
  j["path"] = s.path;
  j["load_seconds"] = seconds;
  j["triangles"] = f.triangles;
  j["instances"] = f.instances;
  j["meshes"] = f.meshes;
  j["materials"] = s.materials.size();
  j["textures"] = s.textures.size();
  j["lights"] = json::array();
  for (const auto& l : s.lights)
    j["lights"].push_back({{"name", l.name},
                           {"type", light_type(l.type)},
                           {"color", vec(l.color)},
                           {"intensity", l.intensity},
                           {"position", vec(l.position)},
                           {"direction", vec(l.direction)}});
  j["cameras"] = json::array();
  for (const auto& c : s.cameras)
    j["cameras"].push_back({{"name", c.name},
                            {"yfov", c.yfov},
                            {"eye", vec(c.eye)},
                            {"forward", vec(c.forward)},
                            {"up", vec(c.up)}});
  const scene::Camera* cam = s.default_camera();
  j["default_camera"] = cam ? json(cam->name) : json(nullptr);
  const scene::Camera vc = view_camera(s);
  j["view_camera"] = {{"name", vc.name},
                      {"framed", cam == nullptr},
                      {"yfov", vc.yfov},
                      {"eye", vec(vc.eye)},
                      {"forward", vec(vc.forward)},
                      {"up", vec(vc.up)}};
  j["animations"] = json::array();
  for (const auto& a : s.animations)
    j["animations"].push_back(
        {{"name", a.name}, {"channels", a.channels.size()}, {"duration", a.duration()}});
  j["bounds"] = f.bounds.empty() ? json(nullptr)
                                 : json{{"min", vec(f.bounds.min)}, {"max", vec(f.bounds.max)}};
  j["environment"] = vec(f.environment);
  j["environment_source"] = scene::environment_source_name(env.source);
  if (env.source == scene::EnvironmentSource::SidecarMap)
    j["environment_map"] = {{"file", s.sidecar.environment_map->file},
                            {"rotation_deg", s.sidecar.environment_map->rotation_deg},
                            {"intensity", s.sidecar.environment_map->intensity}};
  j["light_units"] = s.sidecar.light_units == scene::LightUnits::Radiometric ? "radiometric"
                                                                              : "photometric";
  json grid = json::object();
  if (s.sidecar.probe_counts) {
    const glm::ivec3& c = *s.sidecar.probe_counts;
    grid["counts"] = {c.x, c.y, c.z};
  }
  if (s.sidecar.probe_bounds)
    grid["bounds"] = {{"min", vec(s.sidecar.probe_bounds->min)},
                      {"max", vec(s.sidecar.probe_bounds->max)}};
  j["probe_grid"] = grid;
  j["probe_tracer"] = tracer;  // what --tracer auto takes on the default device
  j["features"] = {{"glossy_materials", f.glossy_materials},
                   {"metal_materials", f.metal_materials},
                   {"textured_materials", f.textured_materials},
                   {"normal_mapped_materials", f.normal_mapped_materials},
                   {"masked_materials", f.masked_materials},
                   {"blended_materials", f.blended_materials},
                   {"double_sided_materials", f.double_sided_materials},
                   {"emissive_materials", f.emissive_materials},
                   {"second_uv_materials", f.second_uv_materials},
                   {"texture_transform_materials", f.texture_transform_materials},
                   {"dielectric_materials", f.dielectric_materials},
                   {"vertex_colored_meshes", f.vertex_colored_meshes},
                   {"skinned_meshes", f.skinned_meshes},
                   {"morphed_meshes", f.morphed_meshes},
                   {"directional_lights", f.directional_lights},
                   {"point_lights", f.point_lights},
                   {"spot_lights", f.spot_lights},
                   {"animated", f.animations > 0}};
  j["left_out"] = json::array();
  for (const auto& item : plan.left_out)
    j["left_out"].push_back({{"what", item.what}, {"why", item.why}});
  j["warnings"] = s.warnings;
  return j;
}

void print_text(const scene::Scene& s, const scene::SceneFeatures& f, const scene::RenderPlan& plan,
                const scene::EnvironmentChoice& env, double seconds, const std::string& tracer) {
  fmt::print("{}  (loaded in {:.2f} s)\n", s.path, seconds);
  fmt::print("  triangles   {} (after instancing)\n", f.triangles);
  fmt::print("  instances   {} of {} meshes\n", f.instances, f.meshes);
  fmt::print("  materials   {} ({} used)\n", s.materials.size(), f.materials_used);
  fmt::print("  textures    {} ({} used)\n", s.textures.size(), f.textures_used);
  fmt::print("  lights      {} directional, {} point, {} spot\n", f.directional_lights,
             f.point_lights, f.spot_lights);
  if (!s.lights.empty()) fmt::print("    units in the file {}\n", light_units(s));
  for (const auto& l : s.lights)
    fmt::print("    {:<12} {:<11} intensity {:g} (radiometric), colour ({:g}, {:g}, {:g})\n", l.name,
               light_type(l.type), l.intensity, l.color.r, l.color.g, l.color.b);
  const scene::Camera* def = s.default_camera();
  fmt::print("  cameras     {}{}\n", s.cameras.size(),
             def ? fmt::format(" (default {})", def->name) : std::string());
  for (const auto& c : s.cameras)
    fmt::print(
        "    {:<12} eye ({:.2f}, {:.2f}, {:.2f}) forward ({:.2f}, {:.2f}, {:.2f}) fov {:.1f} deg\n",
        c.name, c.eye.x, c.eye.y, c.eye.z, c.forward.x, c.forward.y, c.forward.z,
        glm::degrees(c.yfov));
  const scene::Camera vc = view_camera(s);
  fmt::print("  view camera {}: {}{}\n", vc.name, describe_camera(vc),
             def ? "" : " (no camera in the file: the bounding sphere framed for a square view)");
  fmt::print("  animations  {}", f.animations);
  if (f.animations) fmt::print(" ({:.2f} s)", f.animation_duration);
  fmt::print("\n");
  if (!s.deformed.empty())
    fmt::print("  deformed    {} skinned, {} morphed mesh{} (posed every frame in both renderers)\n",
               f.skinned_meshes, f.morphed_meshes, s.deformed.size() == 1 ? "" : "es");
  if (f.bounds.empty())
    fmt::print("  bounds      empty\n");
  else
    fmt::print("  bounds      ({:.3f}, {:.3f}, {:.3f}) .. ({:.3f}, {:.3f}, {:.3f})\n",
               f.bounds.min.x, f.bounds.min.y, f.bounds.min.z, f.bounds.max.x, f.bounds.max.y,
               f.bounds.max.z);
  if (env.source == scene::EnvironmentSource::SidecarMap) {
    const scene::SidecarEnvironmentMap& m = *s.sidecar.environment_map;
    fmt::print("  environment map {} (rotation {:g} deg, intensity {:g}): sidecar\n", m.file, m.rotation_deg,
               m.intensity);
  } else {
    fmt::print("  environment ({:g}, {:g}, {:g}) radiance: {}\n", f.environment.r, f.environment.g,
               f.environment.b, scene::environment_source_name(env.source));
  }
  if (s.sidecar.probe_counts) {
    const glm::ivec3& c = *s.sidecar.probe_counts;
    fmt::print("  probe grid  {} x {} x {} = {} probes{}\n", c.x, c.y, c.z, c.x * c.y * c.z,
               s.sidecar.probe_bounds ? " (sidecar bounds)" : " (scene bounds)");
  } else {
    fmt::print("  probe grid  automatic (no sidecar counts)\n");
  }
  fmt::print("  probe tracer {}\n", tracer);
  fmt::print("features\n");
  fmt::print(
      "  glossy {}, metal {}, textured {}, normal-mapped {}, masked {}, blended {}, "
      "double-sided {}, emissive {} (materials used)\n",
      f.glossy_materials, f.metal_materials, f.textured_materials, f.normal_mapped_materials,
      f.masked_materials, f.blended_materials, f.double_sided_materials, f.emissive_materials);
  fmt::print(
      "  TEXCOORD_1 {}, texture transforms {}, ior/specular {} (materials used); vertex colours {} "
      "(meshes)\n",
      f.second_uv_materials, f.texture_transform_materials, f.dielectric_materials,
      f.vertex_colored_meshes);
  fmt::print("left out\n");
  for (const std::string& line : left_out_lines(plan, "  ")) fmt::print("{}\n", line);
  for (const auto& w : s.warnings) fmt::print("warning: {}\n", w);
}

// Classification's second phase as render would run it with its default grid: the probes with
// no surface near them join what is left out. A scene with no geometry has no grid to tell of.
void add_empty_probes(scene::Scene& s, scene::RenderPlan& plan) {
  if (s.bounds().empty()) return;
  const Placement placement = place_probes(ProbeArgs{}, s);
  const std::vector<bool> near = probes::probes_near_surfaces(placement.grid, s);
  if (const auto n = std::uint32_t(std::count(near.begin(), near.end(), false)); n > 0)
    plan.left_out.push_back(empty_probes_item(n, placement.grid));
}

Action make_info(CLI::App& root) {
  auto opts = std::make_shared<InfoOptions>();
  CLI::App* cmd = root.add_subcommand("info", "scene summary, features, what will be left out");
  cmd->add_option("scene", opts->scene, "glTF 2.0 scene (.gltf or .glb)")->required();
  cmd->add_flag("--json", opts->json, "machine-readable output");
  cmd->add_flag("--decode-textures", opts->decode,
                "decode every texture (slower; checks pixel data, not only image headers)");
  return [opts]() {
    scene::LoadOptions load;
    load.decode_textures = opts->decode;
    auto start = std::chrono::steady_clock::now();
    scene::Scene s = scene::load_scene(opts->scene, load);
    double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    // What render, reference and probes light the scene with when no --sky is given.
    const scene::EnvironmentChoice env = scene::apply_environment(s, std::nullopt);
    scene::SceneFeatures f = scene::analyze(s);
    scene::RenderPlan plan = scene::make_plan(f);
    add_empty_probes(s, plan);
    if (opts->json)
      fmt::print("{}\n", to_json(s, f, plan, env, seconds, auto_tracer_line()).dump(2));
    else
      print_text(s, f, plan, env, seconds, auto_tracer_line());
    return 0;
  };
}

}  // namespace

DDISH_COMMAND(10, make_info);

}  // namespace ddish::app
