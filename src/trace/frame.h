// An orthonormal shading frame built from one unit normal, for moving directions between world
// space and the BSDF's local space (z = normal). The construction is the branchless one of
// Duff et al., "Building an Orthonormal Basis, Revisited" (JCGT 2017): continuous everywhere
// except across z = 0, and free of the precision loss of the earlier Frisvad method near z = -1.
#pragma once

#include <cmath>

#include <glm/glm.hpp>

namespace ddish::trace {

struct Frame {
  glm::vec3 t{1.0f, 0.0f, 0.0f};  // tangent (local x)
  glm::vec3 b{0.0f, 1.0f, 0.0f};  // bitangent (local y)
  glm::vec3 n{0.0f, 0.0f, 1.0f};  // normal (local z)

  // n must be unit length; the result is right-handed (cross(t, b) == n).
  static Frame from_normal(const glm::vec3& n) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float c = n.x * n.y * a;
    Frame f;
    f.t = {1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x};
    f.b = {c, sign + n.y * n.y * a, -n.y};
    f.n = n;
    return f;
  }

  glm::vec3 to_local(const glm::vec3& v) const { return {glm::dot(v, t), glm::dot(v, b), glm::dot(v, n)}; }
  glm::vec3 to_world(const glm::vec3& v) const { return v.x * t + v.y * b + v.z * n; }
};

}  // namespace ddish::trace
