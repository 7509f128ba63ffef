#include "probes/frustum.h"

#include <limits>

namespace ddish::probes {

namespace {

glm::vec4 row(const glm::mat4& m, int r) { return {m[0][r], m[1][r], m[2][r], m[3][r]}; }

Plane normalised(const glm::vec4& p) {
  const float len = glm::length(glm::vec3(p));
  Plane out;
  if (!(len > 0.0f)) {
    // A degenerate plane (an infinite far plane, say) bounds nothing: every point is inside.
    out.normal = glm::vec3(0.0f);
    out.d = std::numeric_limits<float>::infinity();
    return out;
  }
  out.normal = glm::vec3(p) / len;
  out.d = p.w / len;
  return out;
}

}  // namespace

Frustum::Frustum(const glm::mat4& clip_from_world) {
  // A point is inside when -w <= x <= w, -w <= y <= w and 0 <= z <= w (Vulkan depth 0..1):
  // each inequality is a plane made of the clip matrix's rows (Gribb & Hartmann's extraction,
  // with the near plane z >= 0 instead of OpenGL's z >= -w).
  const glm::vec4 x = row(clip_from_world, 0), y = row(clip_from_world, 1),
                  z = row(clip_from_world, 2), w = row(clip_from_world, 3);
  planes_ = {normalised(w + x), normalised(w - x), normalised(w + y),
             normalised(w - y), normalised(z),     normalised(w - z)};
}

bool Frustum::intersects(const scene::Aabb& box, float margin) const {
  if (box.empty()) return false;
  for (const Plane& p : planes_) {
    // The corner furthest along the plane's normal: if even it is outside, the box is.
    const glm::vec3 far_corner(p.normal.x >= 0.0f ? box.max.x : box.min.x,
                               p.normal.y >= 0.0f ? box.max.y : box.min.y,
                               p.normal.z >= 0.0f ? box.max.z : box.min.z);
    if (p.distance(far_corner) < -margin) return false;
  }
  return true;
}

bool Frustum::contains(const glm::vec3& point, float margin) const {
  for (const Plane& p : planes_)
    if (p.distance(point) < -margin) return false;
  return true;
}

}  // namespace ddish::probes
