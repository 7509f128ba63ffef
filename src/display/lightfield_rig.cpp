#include "display/lightfield_rig.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace ddish::display {

void LightFieldParams::validate() const {
  if (views < 1) {
    throw std::invalid_argument("light-field rig needs at least one view, got " +
                                std::to_string(views));
  }
  if (!(view_cone >= 0.0f && view_cone < 3.14159f)) {
    throw std::invalid_argument("light-field view cone " + std::to_string(view_cone) +
                                " rad is outside [0, pi)");
  }
  if (focal_distance && !(*focal_distance > 0.0f)) {
    throw std::invalid_argument("light-field focal distance must be positive");
  }
  if (fov_y && !(*fov_y > 0.0f && *fov_y < 3.14159f)) {
    throw std::invalid_argument("light-field field of view is outside (0, pi)");
  }
}

float lightfield_view_angle(int index, int count, float view_cone) {
  if (count <= 1) return 0.0f;
  return view_cone * (float(index) / float(count - 1) - 0.5f);
}

ViewSet lightfield_rig(const BaseCamera& base, const LightFieldParams& params,
                       const QuiltLayout& layout, float aspect) {
  base.validate();
  params.validate();
  layout.validate();
  if (params.views > layout.cells()) {
    throw std::invalid_argument(std::to_string(params.views) + " light-field views do not fit a " +
                                std::to_string(layout.columns) + "x" +
                                std::to_string(layout.rows) + " quilt");
  }
  if (!(aspect > 0.0f)) throw std::invalid_argument("light-field aspect must be positive");

  // The focal-plane rectangle the base camera frames.
  const float d_base = params.focal_distance.value_or(base.focal_distance);
  const float half_h = d_base * std::tan(0.5f * base.fov_y);
  const float half_w = aspect * half_h;

  // The rig itself: the base camera, or with its own field of view moved along the axis so that
  // field frames the same rectangle (d = half height / tan(fov / 2)).
  BaseCamera rig = base;
  float d = d_base;
  if (params.fov_y) {
    d = half_h / std::tan(0.5f * *params.fov_y);
    const float step_back = d - d_base;
    rig.eye = base.eye - step_back * base.axis_forward();
    rig.fov_y = *params.fov_y;
    rig.focal_distance = d;
    rig.zfar = base.zfar + std::max(step_back, 0.0f);
  }

  ViewSet set;
  set.kind = ViewSetKind::LightField;
  set.name = to_string(set.kind);
  set.layout = layout;
  set.aspect = aspect;
  for (int i = 0; i < params.views; ++i) {
    const float offset = d * std::tan(lightfield_view_angle(i, params.views, params.view_cone));
    scene::View v = sheared_view(rig, offset, 0.0f, d, half_w, half_h, layout.tile_width,
                                 layout.tile_height);
    v.name = indexed_view_name(i, params.views);
    set.views.push_back(v);
  }
  return set;
}

}  // namespace ddish::display
