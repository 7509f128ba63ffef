#include "scene/deformation.h"

#include <cmath>

#include "scene/scene.h"
#include "scene/tangents.h"

namespace ddish::scene {

void Deformation::copy_vertex(std::uint32_t v) {
  auto dup = [v](auto& attr) {
    if (v < attr.size()) attr.push_back(attr[v]);
  };
  for (MorphTarget& t : targets) {
    dup(t.positions);
    dup(t.normals);
    dup(t.tangents);
  }
  const auto sets = std::size_t(influences.sets);
  for (std::size_t k = 0; k < sets; ++k) {
    const std::size_t i = std::size_t(v) * sets + k;
    if (i >= influences.joints.size()) break;
    influences.joints.push_back(influences.joints[i]);
    influences.weights.push_back(influences.weights[i]);
  }
}

void Deformation::capture_rest(const Mesh& mesh) {
  rest_positions = mesh.positions;
  rest_normals = mesh.normals;
  rest_tangents = mesh.tangents;
}

void pose_mesh(Mesh& mesh, std::span<const float> weights, std::span<const glm::mat4> joints) {
  const Deformation& d = mesh.deformation;
  mesh.positions = d.rest_positions;
  mesh.normals = d.rest_normals;
  mesh.tangents = d.rest_tangents;
  apply_morph_targets(d.targets, weights, mesh.positions, mesh.normals, mesh.tangents);
  if (!joints.empty() && !d.influences.empty())
    skin_vertices(d.influences, joints, mesh.positions, mesh.normals, mesh.tangents);
  if (d.generated_normals) {
    generate_normals(mesh);
  } else {
    for (glm::vec3& n : mesh.normals) {
      const float len = glm::length(n);
      n = len > 0.0f && std::isfinite(len) ? n / len : glm::vec3(0.0f, 1.0f, 0.0f);
    }
  }
  for (std::size_t v = 0; v < mesh.tangents.size() && v < mesh.normals.size(); ++v) {
    const glm::vec3& n = mesh.normals[v];
    glm::vec3 t = glm::vec3(mesh.tangents[v]);
    t -= n * glm::dot(n, t);
    const float len = glm::length(t);
    if (len > 1e-12f && std::isfinite(len)) mesh.tangents[v] = glm::vec4(t / len, mesh.tangents[v].w);
  }
  mesh.bounds = Aabb{};
  for (const glm::vec3& p : mesh.positions) mesh.bounds.expand(p);
}

}  // namespace ddish::scene
