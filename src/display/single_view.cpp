#include "display/single_view.h"

#include <cmath>

namespace ddish::display {

ViewSet single_view(const BaseCamera& base, int width, int height, float aspect) {
  base.validate();
  ViewSet set;
  set.kind = ViewSetKind::Single;
  set.name = to_string(set.kind);
  set.layout = layout_from_tiles(1, 1, width, height);
  set.aspect = aspect > 0.0f ? aspect : float(width) / float(height);
  // A sheared view with no offset is the symmetric frustum; going through the shared
  // construction keeps every kind's matrices built the same way.
  const float half_h = base.focal_distance * std::tan(0.5f * base.fov_y);
  scene::View v = sheared_view(base, 0.0f, 0.0f, base.focal_distance, set.aspect * half_h,
                               half_h, width, height);
  v.name = "view";
  set.views.push_back(v);
  return set;
}

}  // namespace ddish::display
