// View-frustum tests for CPU culling, in Vulkan clip conventions (-w <= x, y <= w,
// 0 <= z <= w). Planes come straight from a view-projection matrix (Gribb-Hartmann), so
// off-axis light-field frusta and stereo frusta need nothing special. A plane moved into an
// instance's object space (plane * model) lets the object-space bounds of clusters be tested
// without transforming them: exact for the box, and cheaper than a world box per cluster.
#pragma once

#include <array>
#include <span>

#include <glm/glm.hpp>

namespace ddish::raster {

struct Frustum {
  // ax + by + cz + d >= 0 inside; left, right, bottom, top, near, far.
  std::array<glm::vec4, 6> planes{};

  static Frustum from_view_proj(const glm::mat4& view_proj);
  // The same frustum in the object space of an instance with object-to-world `model`.
  Frustum in_object_space(const glm::mat4& model) const;
  // Whether the box [min, max] may meet the frustum (false only when the box lies wholly
  // outside one plane: conservative, so culling never removes a visible triangle).
  bool meets(const glm::vec3& min, const glm::vec3& max) const;
};

// A box is drawn in a multiview block when any of the block's frusta meets it.
bool any_meets(std::span<const Frustum> frusta, const glm::vec3& min, const glm::vec3& max);

}  // namespace ddish::raster
