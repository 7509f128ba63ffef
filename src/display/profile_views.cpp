#include "display/profile_views.h"

#include "display/single_view.h"

namespace ddish::display {

ViewSet make_view_set(const Profile& profile, const BaseCamera& base) {
  const QuiltLayout& layout = profile.layout;
  ViewSet set;
  switch (profile.model) {
    case CameraModel::Single:
      set = single_view(base, layout.tile_width, layout.tile_height, profile.aspect);
      break;
    case CameraModel::Stereo:
      set = stereo_views(base, profile.stereo, layout.tile_width, layout.tile_height,
                         profile.aspect);
      break;
    case CameraModel::LightField:
      set = lightfield_rig(base, profile.lightfield, layout, profile.aspect);
      break;
    case CameraModel::Grid:
      set = camera_grid(base, profile.grid, layout, profile.aspect);
      break;
  }
  // The profile's atlas (which may be larger than columns × tile) and name, whatever the kind
  // builder assumed: outputs are named and sized by the profile.
  set.layout = layout;
  set.name = profile.name;
  if (!(profile.model == CameraModel::Stereo && profile.stereo.left_eye_fov)) {
    set.aspect = profile.aspect;
  }
  return set;
}

}  // namespace ddish::display
