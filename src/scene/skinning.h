// Linear blend skinning (glTF skins): each vertex is moved by a weighted sum of its joints'
// matrices. A joint matrix is inverse(world of the mesh's node) · world of the joint ·
// inverseBindMatrix, so skinned positions stay in the object space of the node that draws the
// mesh and the instance transform places them as it places any mesh (glTF ignores that node's
// own transform for skinned meshes; the product cancels it).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace ddish::scene {

struct Skin {
  std::string name;
  std::vector<int> joints;               // node indices
  std::vector<glm::mat4> inverse_bind;   // one per joint; identity when the file gives none
};

// A mesh's influences: `sets` groups of four (joint, weight) pairs per vertex (JOINTS_n and
// WEIGHTS_n for n < sets), vertex-major: vertex v's group k is at v * sets + k.
struct SkinInfluences {
  int sets = 0;
  std::vector<glm::uvec4> joints;  // indices into the skin's joints
  std::vector<glm::vec4> weights;  // finite, >= 0
  bool empty() const { return sets == 0; }
  std::size_t vertex_count() const { return sets ? weights.size() / std::size_t(sets) : 0; }
};

inline glm::mat4 joint_matrix(const glm::mat4& inverse_mesh_world, const glm::mat4& joint_world,
                              const glm::mat4& inverse_bind) {
  return inverse_mesh_world * joint_world * inverse_bind;
}

// Why `influences` cannot be skinned by a skin of `joint_count` joints (a joint index out of
// range with a weight above 0), or "" when they can. Joints of weight 0 are never read.
std::string check_influences(const SkinInfluences& influences, std::size_t joint_count);

// Skins the arrays in place: each vertex by Σ w_i · joints[j_i], with the weights divided by
// their sum (files round them; glTF asks for a sum of 1). A vertex whose weights are all 0 is
// left where it is. Normals go through the blend's inverse transpose and tangents through the
// blend itself; neither is normalised here.
void skin_vertices(const SkinInfluences& influences, std::span<const glm::mat4> joints,
                   std::vector<glm::vec3>& positions, std::vector<glm::vec3>& normals,
                   std::vector<glm::vec4>& tangents);

}  // namespace ddish::scene
