#include "app/camera_options.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <glm/glm.hpp>

#include "scene/framing.h"
#include "scene/scene.h"

namespace ddish::app {

void add_camera_options(CLI::App& cmd, CameraArgs& args) {
  cmd.add_option("--camera", args.camera,
                 "camera node name, or eye,target,up as 9 comma-separated numbers "
                 "(default: the scene's default camera)");
  CameraArgs* a = &args;
  cmd.add_option_function<float>(
         "--fov", [a](float deg) { a->fov = deg; },
         "vertical field of view in degrees (default: the camera's, or 45)")
      ->check(CLI::Range(0.1f, 179.0f));
  cmd.add_option("--width", args.width, "image width in pixels (with --display: one view's)")
      ->capture_default_str()
      ->check(CLI::Range(1, 16384))
      ->each([a](const std::string&) { a->width_given = true; });
  cmd.add_option("--height", args.height, "image height in pixels (with --display: one view's)")
      ->capture_default_str()
      ->check(CLI::Range(1, 16384))
      ->each([a](const std::string&) { a->height_given = true; });
}

std::optional<std::vector<float>> parse_pose(const std::string& text) {
  if (text.find(',') == std::string::npos) return std::nullopt;
  std::vector<float> v;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    std::size_t used = 0;
    float f = 0.0f;
    try {
      f = std::stof(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != item.size() || !std::isfinite(f))
      throw std::invalid_argument("--camera: '" + item + "' is not a number (want eye,target,up)");
    v.push_back(f);
  }
  if (v.size() != 9)
    throw std::invalid_argument("--camera wants 9 numbers eye,target,up (got " +
                                std::to_string(v.size()) + ")");
  return v;
}

const scene::Camera* find_camera(const scene::Scene& s, const std::string& name) {
  if (const scene::Camera* c = s.find_camera(name)) return c;
  // glTF cameras are often unnamed and known by their node's name.
  for (const scene::Node& n : s.nodes)
    if (n.name == name && n.camera >= 0 && n.camera < int(s.cameras.size()))
      return &s.cameras[static_cast<std::size_t>(n.camera)];
  return nullptr;
}

scene::Camera resolve_camera(const scene::Scene& s, const CameraArgs& args) {
  if (auto pose = parse_pose(args.camera)) {
    const std::vector<float>& p = *pose;
    const glm::vec3 eye(p[0], p[1], p[2]), target(p[3], p[4], p[5]), up(p[6], p[7], p[8]);
    const glm::vec3 fwd = target - eye;
    if (glm::length(fwd) == 0.0f || glm::length(glm::cross(fwd, up)) == 0.0f)
      throw std::invalid_argument("--camera: eye equals target or up is parallel to the view");
    scene::Camera c;
    c.name = "camera";
    c.eye = eye;
    c.forward = fwd;
    c.up = up;
    c.yfov = glm::radians(args.fov.value_or(kDefaultFovDeg));
    return c;
  }
  const scene::Camera* cam = nullptr;
  if (!args.camera.empty()) {
    cam = find_camera(s, args.camera);
    if (!cam) throw std::invalid_argument("no camera '" + args.camera + "' in " + s.path);
  } else {
    cam = s.default_camera();
    if (!cam) throw std::invalid_argument(s.path + " has no camera; give --camera eye,target,up");
  }
  scene::Camera c = *cam;
  if (args.fov) c.yfov = glm::radians(*args.fov);
  return c;
}

std::string frame_camera_less(scene::Scene& s, const CameraArgs& args, float aspect) {
  if (!s.cameras.empty() || !args.camera.empty()) return "";
  const scene::Sphere sphere = scene::bounding_sphere(s);
  const float fov = glm::radians(args.fov.value_or(kDefaultFovDeg));
  s.cameras.push_back(scene::framing_camera(sphere, fov, aspect));
  return fmt::format(
      "no camera in the scene: framing its bounding sphere (centre ({:.3g}, {:.3g}, {:.3g}), "
      "radius {:.3g} m) from a three-quarter view: {}",
      sphere.center.x, sphere.center.y, sphere.center.z, sphere.radius,
      describe_camera(s.cameras.back()));
}

std::string describe_camera(const scene::Camera& c) {
  const glm::vec3 t = c.eye + glm::normalize(c.forward);
  return fmt::format("eye ({:.3g}, {:.3g}, {:.3g}) target ({:.3g}, {:.3g}, {:.3g}) fov {:.1f} deg",
                     c.eye.x, c.eye.y, c.eye.z, t.x, t.y, t.z, glm::degrees(c.yfov));
}

scene::View make_view(const scene::Scene& s, const CameraArgs& args) {
  return scene::camera_view(resolve_camera(s, args), args.width, args.height);
}

}  // namespace ddish::app
