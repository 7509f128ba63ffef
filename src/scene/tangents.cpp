#include "scene/tangents.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

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

namespace {

// The corner of triangle t at its vertex k (0..2): the angle between its two edges projected
// onto the plane of normal n.
float corner_angle(const glm::vec3& p, const glm::vec3& next, const glm::vec3& prev,
                   const glm::vec3& n) {
  glm::vec3 a = next - p, b = prev - p;
  a -= n * glm::dot(n, a);
  b -= n * glm::dot(n, b);
  const float la = glm::length(a), lb = glm::length(b);
  if (!(la > 0.0f) || !(lb > 0.0f)) return 0.0f;
  return std::acos(std::clamp(glm::dot(a, b) / (la * lb), -1.0f, 1.0f));
}

// Appends a copy of vertex v (all of its attributes) and returns the copy's index.
std::uint32_t copy_vertex(Mesh& mesh, std::uint32_t v) {
  auto dup = [v](auto& attr) {
    if (v < attr.size()) attr.push_back(attr[v]);
  };
  dup(mesh.positions);
  dup(mesh.normals);
  dup(mesh.uvs);
  dup(mesh.uvs1);
  dup(mesh.colors);
  mesh.deformation.copy_vertex(v);  // morph deltas and skin influences follow the copy
  return static_cast<std::uint32_t>(mesh.positions.size() - 1);
}

}  // namespace

void generate_tangents(Mesh& mesh, int texcoord) {
  const std::size_t n = mesh.positions.size();
  const std::vector<glm::vec2>& uvs = mesh.uv_set(texcoord);
  const bool has_uv = uvs.size() == n && mesh.normals.size() == n;
  // Per vertex and orientation (0: positive, 1: negative): the angle-weighted tangent sum and
  // whether any corner contributed to it.
  std::vector<glm::vec3> sum[2] = {std::vector<glm::vec3>(n, glm::vec3(0.0f)),
                                   std::vector<glm::vec3>(n, glm::vec3(0.0f))};
  std::vector<std::uint8_t> used[2] = {std::vector<std::uint8_t>(n, 0),
                                       std::vector<std::uint8_t>(n, 0)};
  std::vector<std::uint8_t> first(n, 2);  // the first orientation a vertex saw (2: none yet)
  const std::size_t tris = mesh.indices.size() / 3;
  std::vector<std::uint8_t> tri_group(tris, 0);
  std::vector<std::int8_t> degenerate(tris, 0);
  for (std::size_t t = 0; has_uv && t < tris; ++t) {
    const std::uint32_t* i = &mesh.indices[3 * t];
    const glm::vec3 e1 = mesh.positions[i[1]] - mesh.positions[i[0]];
    const glm::vec3 e2 = mesh.positions[i[2]] - mesh.positions[i[0]];
    // MikkTSpace's (s, t) = (u, 1 - v): differences in t are minus those in v.
    const glm::vec2 d1(uvs[i[1]].x - uvs[i[0]].x, uvs[i[0]].y - uvs[i[1]].y);
    const glm::vec2 d2(uvs[i[2]].x - uvs[i[0]].x, uvs[i[0]].y - uvs[i[2]].y);
    const float det = d1.x * d2.y - d2.x * d1.y;
    if (!(std::abs(det) > 1e-20f) || !std::isfinite(det)) {
      degenerate[t] = 1;
      continue;
    }
    // dP/ds from [e1 e2] = [dP/ds dP/dt] [d1 d2]; only its direction matters.
    const glm::vec3 ts = (e1 * d2.y - e2 * d1.y) / det;
    const std::uint8_t g = det > 0.0f ? 0 : 1;
    tri_group[t] = g;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = i[k];
      const glm::vec3& nrm = mesh.normals[v];
      glm::vec3 tp = ts - nrm * glm::dot(nrm, ts);
      const float len = glm::length(tp);
      if (!(len > 1e-20f) || !std::isfinite(len)) continue;
      const float angle = corner_angle(mesh.positions[v], mesh.positions[i[(k + 1) % 3]],
                                       mesh.positions[i[(k + 2) % 3]], nrm);
      sum[g][v] += tp / len * angle;
      used[g][v] = 1;
      if (first[v] == 2) first[v] = g;
    }
  }
  // Degenerate triangles take their vertices' first orientation, so they never split a vertex.
  for (std::size_t t = 0; t < tris; ++t)
    if (degenerate[t]) tri_group[t] = first[mesh.indices[3 * t]] == 1 ? 1 : 0;

  // A vertex used by both orientations: the negative group moves to a copy.
  std::vector<std::uint32_t> negative_copy(n, std::uint32_t(-1));
  for (std::size_t v = 0; v < n; ++v)
    if (used[0][v] && used[1][v]) negative_copy[v] = copy_vertex(mesh, std::uint32_t(v));
  for (std::size_t t = 0; t < tris; ++t) {
    if (tri_group[t] != 1) continue;
    for (int k = 0; k < 3; ++k) {
      std::uint32_t& v = mesh.indices[3 * t + std::size_t(k)];
      if (v < n && negative_copy[v] != std::uint32_t(-1)) v = negative_copy[v];
    }
  }

  mesh.tangents.assign(mesh.positions.size(), glm::vec4(0.0f));
  auto finish = [&](std::size_t out, const glm::vec3& s, float w) {
    const glm::vec3 nrm = mesh.normals[out];
    glm::vec3 t = s - nrm * glm::dot(nrm, s);
    const float len = glm::length(t);
    t = len > 1e-12f && std::isfinite(len) ? t / len : any_orthogonal(nrm);
    mesh.tangents[out] = glm::vec4(t, w);
  };
  for (std::size_t v = 0; v < n; ++v) {
    if (negative_copy[v] != std::uint32_t(-1)) {
      finish(v, sum[0][v], 1.0f);
      finish(negative_copy[v], sum[1][v], -1.0f);
    } else if (used[1][v]) {
      finish(v, sum[1][v], -1.0f);
    } else {
      finish(v, sum[0][v], 1.0f);
    }
  }
}

}  // namespace ddish::scene
