// A deformable mesh's rest pose and what deforms it (morph targets, skin influences), kept
// beside the posed vertex arrays that Scene::Mesh holds. Scene::pose writes the posed arrays;
// the tracer and the rasterizer read only those, so both draw the same pose.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "scene/morph.h"
#include "scene/skinning.h"

namespace ddish::scene {

struct Mesh;

struct Deformation {
  std::vector<MorphTarget> targets;
  SkinInfluences influences;
  // The rest pose (bind pose, all weights 0), captured when the mesh is loaded.
  std::vector<glm::vec3> rest_positions;
  std::vector<glm::vec3> rest_normals;
  std::vector<glm::vec4> rest_tangents;
  bool generated_normals = false;  // the file has none: they are generated again from the pose

  bool empty() const { return targets.empty() && influences.empty(); }
  // Appends a copy of vertex v's morph deltas and influences (a vertex split by tangent
  // generation keeps deforming like the vertex it came from).
  void copy_vertex(std::uint32_t v);
  // Records the mesh's current arrays as its rest pose.
  void capture_rest(const Mesh& mesh);
};

// Poses `mesh` from its rest pose: morph targets with `weights`, then skinning with the joint
// matrices `joints` (empty: not skinned). Normals come out unit length (generated again when the
// file had none) and tangents unit and orthogonal to them; the bounds follow the new positions.
void pose_mesh(Mesh& mesh, std::span<const float> weights, std::span<const glm::mat4> joints);

}  // namespace ddish::scene
