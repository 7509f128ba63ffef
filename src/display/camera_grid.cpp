#include "display/camera_grid.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace ddish::display {

void GridParams::validate() const {
  if (columns < 1 || rows < 1) {
    throw std::invalid_argument("camera grid " + std::to_string(columns) + "x" +
                                std::to_string(rows) + " needs at least one camera");
  }
  if (spacing && !(*spacing >= 0.0f)) {
    throw std::invalid_argument("camera grid spacing must be >= 0");
  }
  if (!(spacing_ratio >= 0.0f)) {
    throw std::invalid_argument("camera grid spacing ratio must be >= 0");
  }
  if (recenter_distance && !(*recenter_distance > 0.0f)) {
    throw std::invalid_argument("camera grid recentering distance must be positive");
  }
}

ViewSet camera_grid(const BaseCamera& base, const GridParams& params, const QuiltLayout& layout,
                    float aspect) {
  base.validate();
  params.validate();
  layout.validate();
  const int count = params.columns * params.rows;
  if (count > layout.cells()) {
    throw std::invalid_argument("a " + std::to_string(params.columns) + "x" +
                                std::to_string(params.rows) + " camera grid does not fit a " +
                                std::to_string(layout.columns) + "x" +
                                std::to_string(layout.rows) + " atlas");
  }
  if (!(aspect > 0.0f)) throw std::invalid_argument("camera grid aspect must be positive");

  const float d = params.recenter_distance.value_or(base.focal_distance);
  const float spacing = params.spacing.value_or(params.spacing_ratio * d);
  const float half_h = d * std::tan(0.5f * base.fov_y);
  const float half_w = aspect * half_h;

  ViewSet set;
  set.kind = ViewSetKind::Grid;
  set.name = to_string(set.kind);
  set.layout = layout;
  set.aspect = aspect;
  for (int row = 0; row < params.rows; ++row) {
    for (int col = 0; col < params.columns; ++col) {
      // Centred on the base eye: offsets run symmetrically from -(n-1)/2 to +(n-1)/2 spacings.
      const float x = (float(col) - 0.5f * float(params.columns - 1)) * spacing;
      const float y = (float(row) - 0.5f * float(params.rows - 1)) * spacing;
      scene::View v = sheared_view(base, x, y, d, half_w, half_h, layout.tile_width,
                                   layout.tile_height);
      v.name = indexed_view_name(row * params.columns + col, count);
      set.views.push_back(v);
    }
  }
  return set;
}

}  // namespace ddish::display
