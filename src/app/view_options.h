// The display options that `ddish render` and `ddish reference` share (--display, --views,
// --focal-distance) and the one function that turns them, with the camera options, into the
// views of a frame, so a rendered quilt and its reference are taken from exactly the same
// cameras.
//
//   --display single (default)  the one view of the camera options (--width × --height)
//   --display stereo            the stereo-hmd profile
//   --display NAME|PATH         a profile from displays/ (display::load_profile)
//
// With a profile, --width / --height override the tile (one view's) size; the atlas is then
// columns × tile by rows × tile. --views N changes how many views a light-field profile has:
// the profile's quilt layout is kept when N equals its views, otherwise the layout is recomputed
// (choose_quilt_layout). Stereo, single and camera-grid models have a fixed number of views, so
// --views must then equal it.
#pragma once

#include <optional>
#include <string>

#include "app/camera_options.h"
#include "display/profile.h"
#include "display/quilt_layout.h"
#include "display/view_set.h"

namespace CLI {
class App;
}

namespace ddish::app {

// The largest atlas side a recomputed layout may have (pixels): beyond this no image tool we
// write for reads the file comfortably, and --views is then asking for more than fits.
inline constexpr int kMaxAtlasSide = 16384;

struct DisplayArgs {
  std::string display;                  // "single", "stereo", a profile name or a path
  std::optional<int> views;             // --views N
  std::optional<float> focal_distance;  // --focal-distance M
};

// `--display list`: one line per profile in displays/ (name, views, quilt, tile, panel).
std::string display_list();

// Registers --display, --views and --focal-distance.
void add_display_options(CLI::App& cmd, DisplayArgs& args);

// What --display and --views resolve to before the scene is loaded: nothing for the single view,
// else the profile with the overrides applied (views, tile size, layout, focal distance).
struct DisplayChoice {
  std::optional<display::Profile> profile;
  bool single() const { return !profile.has_value(); }
};

// Loads the profile and applies --views, --width/--height and --focal-distance. Throws
// std::invalid_argument or display::ProfileError with one line: --views below 1 or not allowed
// by the camera model, a non-positive focal distance, an unknown profile (the message lists the
// profiles there are), a layout that cannot fit.
DisplayChoice resolve_display(const DisplayArgs& display, const CameraArgs& camera);

// Width / height of one view: the profile's tile, else --width / --height.
float view_aspect(const DisplayChoice& choice, const CameraArgs& camera);

// The layout for `views` tiles of tile_width × tile_height: the fewest empty cells first, then
// the atlas closest to square, then more columns. 48 tiles of 420 × 560 give 8 × 6 (3360 ×
// 3360), 8 give 4 × 2, 2 give 2 × 1. Throws std::invalid_argument when the atlas would exceed
// kMaxAtlasSide on a side.
display::QuiltLayout choose_quilt_layout(int views, int tile_width, int tile_height);

// The frame's views for the scene as posed now. The base camera is the camera options' camera;
// its focal distance is --focal-distance, else display::focal_distance_to_scene_center.
display::ViewSet make_frame_views(const scene::Scene& scene, const DisplayChoice& choice,
                                  const DisplayArgs& display, const CameraArgs& camera);
// The same from a camera the caller posed (the live window's interactive camera); --camera is
// then not looked at, --width / --height and the profile are.
display::ViewSet make_frame_views(const scene::Scene& scene, const DisplayChoice& choice,
                                  const DisplayArgs& display, const CameraArgs& camera,
                                  const scene::Camera& posed_camera);

}  // namespace ddish::app
