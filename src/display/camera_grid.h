// A camera grid: columns × rows parallel cameras on a plane facing the base camera's forward
// direction, `spacing` apart, each frustum sheared so that all of them frame the base camera's
// rectangle at the recentering distance (the classic two-plane light field: points at that
// distance have no parallax between neighbouring cameras, horizontally or vertically).
//
// Order: view = row · columns + column, column 0 the leftmost camera and row 0 the lowest, so a
// grid written as a quilt of the same columns × rows puts each camera where it sits.
#pragma once

#include <optional>

#include "display/view_set.h"

namespace ddish::display {

struct GridParams {
  int columns = 1;
  int rows = 1;
  // Distance between neighbouring cameras in scene units; if unset, spacing_ratio times the
  // recentering distance (so one profile suits scenes of any scale).
  std::optional<float> spacing;
  float spacing_ratio = 0.02f;
  // Where the frusta recentre; the base camera's focal distance if unset.
  std::optional<float> recenter_distance;

  // Throws std::invalid_argument (one line) on non-positive counts, negative spacing or a
  // non-positive recentering distance.
  void validate() const;
};

// The grid's views, each layout.tile_width × layout.tile_height pixels, projections built for
// `aspect`. Throws std::invalid_argument when the grid has more cameras than the layout has cells.
ViewSet camera_grid(const BaseCamera& base, const GridParams& params, const QuiltLayout& layout,
                    float aspect);

}  // namespace ddish::display
