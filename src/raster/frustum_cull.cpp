#include "raster/frustum_cull.h"

namespace ddish::raster {

Frustum Frustum::from_view_proj(const glm::mat4& m) {
  // Rows of the matrix (glm is column-major: m[column][row]).
  const glm::vec4 r0(m[0][0], m[1][0], m[2][0], m[3][0]);
  const glm::vec4 r1(m[0][1], m[1][1], m[2][1], m[3][1]);
  const glm::vec4 r2(m[0][2], m[1][2], m[2][2], m[3][2]);
  const glm::vec4 r3(m[0][3], m[1][3], m[2][3], m[3][3]);
  // Vulkan depth runs 0..w, so the near plane is z >= 0 (r2), not z >= -w.
  return Frustum{{r3 + r0, r3 - r0, r3 + r1, r3 - r1, r2, r3 - r2}};
}

Frustum Frustum::in_object_space(const glm::mat4& model) const {
  // A world point p = model * q is inside plane P when dot(P, p) >= 0, i.e. dot(P * model, q):
  // the object-space plane is the row vector P times model, which is transpose(model) * P.
  const glm::mat4 t = glm::transpose(model);
  Frustum out;
  for (std::size_t i = 0; i < planes.size(); ++i) out.planes[i] = t * planes[i];
  return out;
}

bool Frustum::meets(const glm::vec3& min, const glm::vec3& max) const {
  for (const glm::vec4& p : planes) {
    // The box corner furthest along the plane's normal: if even it is outside, all are.
    const glm::vec3 far(p.x >= 0.0f ? max.x : min.x, p.y >= 0.0f ? max.y : min.y,
                        p.z >= 0.0f ? max.z : min.z);
    if (p.x * far.x + p.y * far.y + p.z * far.z + p.w < 0.0f) return false;
  }
  return true;
}

bool any_meets(std::span<const Frustum> frusta, const glm::vec3& min, const glm::vec3& max) {
  for (const Frustum& f : frusta)
    if (f.meets(min, max)) return true;
  return false;
}

}  // namespace ddish::raster
