// The camera options that `ddish reference` and `ddish render` share (--camera NODE or
// eye,target,up; --fov; --width/--height) and the view they make, so that a rendered image and
// its reference are taken from exactly the same view.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "scene/scene.h"
#include "scene/view.h"

namespace CLI {
class App;
}

namespace ddish::app {

inline constexpr float kDefaultFovDeg = 45.0f;  // for --camera eye,target,up without --fov

struct CameraArgs {
  std::string camera;        // node / camera name, or "ex,ey,ez,tx,ty,tz,ux,uy,uz"
  std::optional<float> fov;  // degrees, vertical
  int width = 512;
  int height = 512;
  // Whether --width / --height were given: with a display profile they override its tile size,
  // without them the profile's size stands.
  bool width_given = false;
  bool height_given = false;
};

// Registers --camera, --fov, --width and --height (with `args`' sizes as defaults).
void add_camera_options(CLI::App& cmd, CameraArgs& args);

// "ex,ey,ez,tx,ty,tz,ux,uy,uz" -> nine floats; nothing if the text has no comma; throws
// std::invalid_argument for a malformed pose.
std::optional<std::vector<float>> parse_pose(const std::string& text);

// A camera by its name or its node's name; nullptr when there is none.
const scene::Camera* find_camera(const scene::Scene& scene, const std::string& name);

// The scene camera the options describe, posed now (a camera node follows its animation), with
// --fov applied; --camera eye,target,up makes a camera named "camera". Throws
// std::invalid_argument naming what is wrong.
scene::Camera resolve_camera(const scene::Scene& scene, const CameraArgs& args);

// When the scene has no camera and --camera is empty, adds scene/framing.h's framing camera
// for views of width / height = aspect (and --fov, else kDefaultFovDeg) as the scene's default
// camera, and returns the run-log line that says so; otherwise changes nothing and returns "".
// Call it once, on the scene as posed at the first frame: the camera then stays put while an
// animation moves the scene's bounds.
std::string frame_camera_less(scene::Scene& scene, const CameraArgs& args, float aspect);

// One line: "eye (x, y, z) target (x, y, z) fov F deg" (the target one unit ahead).
std::string describe_camera(const scene::Camera& camera);

// The view the options describe for the scene as posed now (a camera node follows its
// animation). Throws std::invalid_argument naming what is wrong.
scene::View make_view(const scene::Scene& scene, const CameraArgs& args);

}  // namespace ddish::app
