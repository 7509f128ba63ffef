// Morph targets (a glTF primitive's "targets"): per-vertex displacements of a mesh's positions,
// normals and tangents, added with weights that belong to the node drawing the mesh (the mesh's
// "weights" by default, the node's "weights" over them, a "weights" animation channel over both).
#pragma once

#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace ddish::scene {

struct MorphTarget {
  // Displacements, one per vertex of the mesh; an attribute the target does not move is empty.
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec3> tangents;  // xyz only: glTF does not morph the handedness
};

// Adds weights[k] · targets[k] to the arrays (which have the targets' vertex count): the glTF
// morphed value is rest + Σ weight · delta. Normals and tangents are left unnormalised (the
// caller normalises after skinning). Targets without a weight, and weights of 0, add nothing.
void apply_morph_targets(std::span<const MorphTarget> targets, std::span<const float> weights,
                         std::vector<glm::vec3>& positions, std::vector<glm::vec3>& normals,
                         std::vector<glm::vec4>& tangents);

}  // namespace ddish::scene
