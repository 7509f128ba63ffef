// The view set a display profile asks for, built around a base camera: how the app turns
// `--display NAME` and the scene camera into the views of one frame.
//
//   Profile profile = load_profile("looking-glass-portrait");
//   BaseCamera base = base_camera(*scene.default_camera(),
//                                 focal_distance_to_scene_center(scene, cam.eye, cam.forward));
//   ViewSet views = make_view_set(profile, base);   // 48 views of 420 × 560, 8 × 6 quilt
#pragma once

#include "display/profile.h"
#include "display/view_set.h"

namespace ddish::display {

// Throws std::invalid_argument (one line) when the base camera is degenerate.
ViewSet make_view_set(const Profile& profile, const BaseCamera& base);

}  // namespace ddish::display
