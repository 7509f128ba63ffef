#include "scene/morph.h"

#include <algorithm>

namespace ddish::scene {

void apply_morph_targets(std::span<const MorphTarget> targets, std::span<const float> weights,
                         std::vector<glm::vec3>& positions, std::vector<glm::vec3>& normals,
                         std::vector<glm::vec4>& tangents) {
  const std::size_t n = std::min(targets.size(), weights.size());
  for (std::size_t k = 0; k < n; ++k) {
    const float w = weights[k];
    if (w == 0.0f) continue;
    const MorphTarget& t = targets[k];
    if (t.positions.size() == positions.size())
      for (std::size_t v = 0; v < positions.size(); ++v) positions[v] += w * t.positions[v];
    if (t.normals.size() == normals.size())
      for (std::size_t v = 0; v < normals.size(); ++v) normals[v] += w * t.normals[v];
    if (t.tangents.size() == tangents.size())
      for (std::size_t v = 0; v < tangents.size(); ++v)
        tangents[v] += glm::vec4(w * t.tangents[v], 0.0f);
  }
}

}  // namespace ddish::scene
