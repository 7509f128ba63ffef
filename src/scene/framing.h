// The camera ddish uses when a scene has none and the command line names none (53 of 60 of
// Khronos's sample models have no camera): it frames the scene's bounding sphere from a
// three-quarter view, as glTF viewers do, so that every model renders with no options.
#pragma once

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace ddish::scene {

// The framing camera looks at the sphere from kFramingAzimuthDeg about +Y from the glTF front
// (+Z) towards +X and kFramingElevationDeg above the horizon: a three-quarter view that shows a
// model's front, one side and its top, with +Y up.
inline constexpr float kFramingAzimuthDeg = 45.0f;
inline constexpr float kFramingElevationDeg = 25.0f;
// The sphere's silhouette spans this fraction of the image's shorter side (the narrower field of
// view), so the model does not touch the border: a centred sphere covers pi / 4 * 0.9^2 = 63.6 %
// of a square image.
inline constexpr float kFramingFill = 0.9f;
// The name the framing camera goes by (`ddish info`, the run log, a view's name).
inline constexpr const char* kFramingCameraName = "framing";

struct Sphere {
  glm::vec3 center{0.0f};
  float radius = 0.0f;
};

// A sphere around every vertex of every instance as posed now: centred on the world bounds,
// with the radius of the farthest vertex (tighter than the box's corner, exact for a sphere
// mesh). Empty scenes give radius 0 at the origin.
Sphere bounding_sphere(const Scene& scene);

// The framing camera for views of width / height = aspect and vertical field yfov (radians):
// the sphere's silhouette fills kFramingFill of the narrower field. Its near and far planes
// bracket the sphere. node = -1: it is not part of the hierarchy and does not move with pose().
// A sphere of radius 0 (no geometry, or a single point) is framed as if its radius were 1.
Camera framing_camera(const Sphere& sphere, float yfov, float aspect);

}  // namespace ddish::scene
