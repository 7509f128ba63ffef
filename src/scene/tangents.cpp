#include "scene/tangents.h"

#include <cmath>

namespace ddish::scene {

namespace {

// A unit vector orthogonal to n (n unit), stable for every direction.
glm::vec3 any_orthogonal(const glm::vec3& n) {
  glm::vec3 a = std::abs(n.x) < 0.9f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
  return glm::normalize(glm::cross(a, n));
}

}  // namespace

void generate_normals(Mesh& mesh) {
  std::vector<glm::vec3> sum(mesh.positions.size(), glm::vec3(0.0f));
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    std::uint32_t i0 = mesh.indices[t], i1 = mesh.indices[t + 1], i2 = mesh.indices[t + 2];
    glm::vec3 n = glm::cross(mesh.positions[i1] - mesh.positions[i0],
                             mesh.positions[i2] - mesh.positions[i0]);
    sum[i0] += n;
    sum[i1] += n;
    sum[i2] += n;
  }
  mesh.normals.resize(mesh.positions.size());
  for (std::size_t v = 0; v < sum.size(); ++v) {
    float len = glm::length(sum[v]);
    mesh.normals[v] = len > 0.0f ? sum[v] / len : glm::vec3(0.0f, 1.0f, 0.0f);
  }
}

void generate_tangents(Mesh& mesh) {
  std::size_t n = mesh.positions.size();
  std::vector<glm::vec3> tan(n, glm::vec3(0.0f));
  std::vector<glm::vec3> bit(n, glm::vec3(0.0f));
  bool has_uv = mesh.uvs.size() == n;
  for (std::size_t t = 0; has_uv && t + 2 < mesh.indices.size(); t += 3) {
    std::uint32_t i[3] = {mesh.indices[t], mesh.indices[t + 1], mesh.indices[t + 2]};
    glm::vec3 e1 = mesh.positions[i[1]] - mesh.positions[i[0]];
    glm::vec3 e2 = mesh.positions[i[2]] - mesh.positions[i[0]];
    glm::vec2 d1 = mesh.uvs[i[1]] - mesh.uvs[i[0]];
    glm::vec2 d2 = mesh.uvs[i[2]] - mesh.uvs[i[0]];
    float det = d1.x * d2.y - d2.x * d1.y;
    if (std::abs(det) < 1e-20f) continue;  // no UV gradient on this triangle
    // Solving [e1 e2] = [T B] [d1 d2] gives dP/du and dP/dv; scaling by |det| instead of
    // dividing by det keeps the orientation and weights each triangle by its UV area.
    float s = det > 0.0f ? 1.0f : -1.0f;
    glm::vec3 tu = s * (e1 * d2.y - e2 * d1.y);
    glm::vec3 tv = s * (e2 * d1.x - e1 * d2.x);
    for (std::uint32_t k : i) {
      tan[k] += tu;
      bit[k] += tv;
    }
  }
  mesh.tangents.resize(n);
  for (std::size_t v = 0; v < n; ++v) {
    glm::vec3 nrm = mesh.normals[v];
    glm::vec3 t = tan[v] - nrm * glm::dot(nrm, tan[v]);
    float len = glm::length(t);
    t = len > 1e-12f ? t / len : any_orthogonal(nrm);
    float w = glm::dot(glm::cross(nrm, t), bit[v]) < 0.0f ? -1.0f : 1.0f;
    mesh.tangents[v] = glm::vec4(t, w);
  }
}

}  // namespace ddish::scene
