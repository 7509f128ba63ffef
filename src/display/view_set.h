// A view set: the ordered scene::Views one frame renders for one display (a single monitor view,
// two eyes, a light-field rig, a camera grid), and where each lands in the output atlas. Every
// kind is built from one BaseCamera, so the same scene camera drives any display; the kinds live
// in their own files (single_view.h, stereo.h, lightfield_rig.h, camera_grid.h) and
// profile_views.h builds the set a display profile asks for.
//
// View order is the atlas order: view i goes to QuiltLayout::tile(i) (view 0 bottom-left).
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "display/quilt_layout.h"
#include "scene/view.h"

namespace ddish::scene {
struct Camera;
struct Scene;
}  // namespace ddish::scene

namespace ddish::display {

// The camera a view set is built around: a pinhole at `eye` looking along `forward`, and the
// focal (zero-parallax) plane at `focal_distance` along `forward`. Stereo and light-field cameras
// are offset from `eye` along the camera's right (and, for grids, up) axes and keep `forward`.
struct BaseCamera {
  glm::vec3 eye{0.0f};
  glm::vec3 forward{0.0f, 0.0f, -1.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float fov_y = 0.785398163f;  // vertical field of view, radians
  float focal_distance = 1.0f;
  float znear = 0.01f;
  float zfar = 1000.0f;

  // Unit camera axes (right = forward × up, as glm::lookAt builds the view matrix).
  glm::vec3 axis_forward() const;
  glm::vec3 axis_right() const;
  glm::vec3 axis_up() const;
  // Throws std::invalid_argument (one line) on a degenerate camera: zero forward, up parallel to
  // forward, fov outside (0, π), non-positive focal distance or clip planes.
  void validate() const;
};

// The base camera of a scene camera (its pose now) with the given focal distance.
BaseCamera base_camera(const scene::Camera& camera, float focal_distance);

// The distance from `eye` along `forward` to the plane through the centre of the scene's bounds:
// the default focal plane, so the middle of the scene shows with no parallax. Falls back to the
// straight-line distance when the centre is not in front of the camera, and to 1 for an empty
// scene or an eye at the centre.
float focal_distance_to_scene_center(const scene::Scene& scene, const glm::vec3& eye,
                                     const glm::vec3& forward);

enum class ViewSetKind { Single, Stereo, LightField, Grid };
const char* to_string(ViewSetKind kind);

struct ViewSet {
  ViewSetKind kind = ViewSetKind::Single;
  std::string name;  // the display profile's name, or the kind's; names output files
  std::vector<scene::View> views;
  QuiltLayout layout;  // every view is layout.tile_width × layout.tile_height pixels
  float aspect = 1.0f;  // display aspect (width / height) the projections are built for

  std::size_t size() const { return views.size(); }
};

// A camera parallel to `base`, moved by `offset_right` along its right axis and `offset_up`
// along its up axis, whose off-axis frustum (scene::frustum_vk) frames exactly the rectangle
// centred on the base camera's axis at `distance`, of half extents half_width × half_height: the
// shared construction of stereo eyes, light-field rigs and camera grids (no toe-in, so vertical
// lines stay vertical and the views share one focal plane).
scene::View sheared_view(const BaseCamera& base, float offset_right, float offset_up,
                         float distance, float half_width, float half_height, int width,
                         int height);

// "view_07": zero-padded to the digits of count - 1, so names sort in view order.
std::string indexed_view_name(int index, int count);

}  // namespace ddish::display
