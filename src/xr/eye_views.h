// Located eyes as scene::Views. The headset's LOCAL space is placed in the scene at a base
// camera: its origin at the camera's eye, its -Z along the camera's forward, +Y along its up. An
// eye's pose (position and orientation in LOCAL) becomes a camera there, and its FOV angles
// (XrFovf: left and down negative) the asymmetric frustum, through display::fov_view: the same
// convention as `ddish render --display stereo` with per-eye angles.
#pragma once

#include <openxr/openxr.h>

#include "display/view_set.h"
#include "scene/view.h"

namespace ddish::xr {

scene::View eye_view(const display::BaseCamera& origin, const XrPosef& eye, const XrFovf& fov, int width,
                     int height);

}  // namespace ddish::xr
