// The light-field rig of the Looking Glass camera model: N parallel cameras spread over a
// horizontal view cone, all framing one focal-plane rectangle (horizontal parallax only).
//
// With d the distance from the rig to the focal plane and cone the total view cone, camera i of N
// sits at rig + d·tan(θᵢ)·right, θᵢ = cone·(i/(N−1) − ½) (θ = 0 for N = 1), looks along the rig's
// forward axis, and has an off-axis frustum that frames the same focal-plane rectangle as the
// base camera. View 0 is the leftmost camera (θ = −cone/2), which the quilt puts bottom-left.
//
// What a point does across views (camera i moving right): a point on the focal plane stays on
// the same pixel; a point nearer than the focal plane moves left in the image (opposite to the
// cameras); a point beyond it moves right (with them). Derivation in docs/displays.md.
#pragma once

#include <optional>

#include "display/view_set.h"

namespace ddish::display {

struct LightFieldParams {
  int views = 48;
  float view_cone = 0.6981317f;  // total, radians (40°, the Looking Glass default)
  // The focal plane's distance from the base camera; the base camera's focal distance if unset.
  std::optional<float> focal_distance;
  // A vertical field of view for the rig (Looking Glass software defaults to 14°). The rig keeps
  // the base camera's focal-plane rectangle and stands back (or forward) on the base camera's axis
  // until this field frames it, so the scene stays framed as the scene camera frames it.
  std::optional<float> fov_y;

  // Throws std::invalid_argument (one line) unless views >= 1, 0 <= cone < 180° and the optional
  // distance / field of view are valid.
  void validate() const;
};

// θᵢ for camera `index` of `count` over a total cone `view_cone` (radians).
float lightfield_view_angle(int index, int count, float view_cone);

// The rig's views, each layout.tile_width × layout.tile_height pixels, projections built for
// `aspect`. Throws std::invalid_argument when params.views exceeds the layout's cells.
ViewSet lightfield_rig(const BaseCamera& base, const LightFieldParams& params,
                       const QuiltLayout& layout, float aspect);

}  // namespace ddish::display
