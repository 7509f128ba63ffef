#include "scene/skinning.h"

#include <cmath>

namespace ddish::scene {

std::string check_influences(const SkinInfluences& influences, std::size_t joint_count) {
  const std::size_t sets = std::size_t(influences.sets);
  for (std::size_t i = 0; i < influences.joints.size(); ++i)
    for (int c = 0; c < 4; ++c)
      if (influences.weights[i][c] > 0.0f && influences.joints[i][c] >= joint_count)
        return "vertex " + std::to_string(i / sets) + " uses joint " +
               std::to_string(influences.joints[i][c]) + ", but the skin has " +
               std::to_string(joint_count) + (joint_count == 1 ? " joint" : " joints");
  return "";
}

void skin_vertices(const SkinInfluences& influences, std::span<const glm::mat4> joints,
                   std::vector<glm::vec3>& positions, std::vector<glm::vec3>& normals,
                   std::vector<glm::vec4>& tangents) {
  const std::size_t sets = std::size_t(influences.sets);
  const std::size_t n = std::min(positions.size(), influences.vertex_count());
  for (std::size_t v = 0; v < n; ++v) {
    glm::mat4 blend(0.0f);
    float sum = 0.0f;
    for (std::size_t k = 0; k < sets; ++k) {
      const glm::uvec4& j = influences.joints[v * sets + k];
      const glm::vec4& w = influences.weights[v * sets + k];
      for (int c = 0; c < 4; ++c) {
        // check_influences ran at load: a joint out of range has weight 0 and is skipped.
        if (!(w[c] > 0.0f) || j[c] >= joints.size()) continue;
        blend += w[c] * joints[j[c]];
        sum += w[c];
      }
    }
    if (!(sum > 0.0f)) continue;
    blend /= sum;
    positions[v] = glm::vec3(blend * glm::vec4(positions[v], 1.0f));
    const glm::mat3 m(blend);
    if (v < normals.size()) {
      // The cofactor matrix is det · inverse-transpose: cheaper, and defined for any blend.
      // Its sign follows det, so a mirroring blend still keeps normals on the outside.
      const glm::mat3 cofactor(glm::cross(m[1], m[2]), glm::cross(m[2], m[0]),
                               glm::cross(m[0], m[1]));
      const float det = glm::dot(m[0], cofactor[0]);
      normals[v] = (det < 0.0f ? -1.0f : 1.0f) * (cofactor * normals[v]);
    }
    if (v < tangents.size()) tangents[v] = glm::vec4(m * glm::vec3(tangents[v]), tangents[v].w);
  }
}

}  // namespace ddish::scene
