// Stereo view sets: two eyes IPD apart along the camera's right axis, parallel (no toe-in, which
// would tilt the two images' vertical lines against each other and cause vertical disparity).
// View 0 is the left eye, view 1 the right eye; the layout is 2 × 1, i.e. side by side.
//
// Three frustum choices:
//  - per-eye field-of-view angles (what an OpenXR runtime reports for each eye as XrFovf: signed
//    angles, left and down negative). Each eye's frustum is exactly those angles; a headset's eyes
//    usually see further outwards than inwards, so the two frusta mirror each other.
//  - converged (the default without angles): both frusta frame the same rectangle of the base
//    camera's view at the convergence (screen) distance; points there have zero disparity.
//  - parallel: both frusta are the base camera's symmetric one; points at infinity have zero
//    disparity.
#pragma once

#include <optional>

#include "display/view_set.h"

namespace ddish::display {

// A field of view as OpenXR's XrFovf gives it: radians from the view direction, left and down
// negative for an ordinary frustum.
struct EyeFov {
  float left = 0.0f;
  float right = 0.0f;
  float up = 0.0f;
  float down = 0.0f;
};

struct StereoParams {
  float ipd = 0.063f;  // interpupillary distance, scene units (metres)
  // Both or neither; when given they fix the frusta (and the aspect) of the eyes.
  std::optional<EyeFov> left_eye_fov;
  std::optional<EyeFov> right_eye_fov;
  bool converge = true;  // without per-eye angles: converged at the screen, or parallel
  // The zero-disparity distance when converged; the base camera's focal distance if unset.
  std::optional<float> convergence_distance;

  // Throws std::invalid_argument (one line) on a negative IPD, a single eye's angles, or angles
  // that do not make a frustum (left >= right, down >= up, or beyond ±90°).
  void validate() const;
};

// The two eyes, each eye_width × eye_height pixels, projections built for `aspect`
// (eye_width / eye_height when aspect <= 0; unused with per-eye angles).
ViewSet stereo_views(const BaseCamera& base, const StereoParams& params, int eye_width,
                     int eye_height, float aspect = 0.0f);

// A camera at base.eye + offset_right · right with the frustum of `fov` (OpenXR angles).
scene::View fov_view(const BaseCamera& base, float offset_right, const EyeFov& fov, int width,
                     int height);

}  // namespace ddish::display
