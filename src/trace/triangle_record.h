// Per-triangle shading data in one compact record: what a hit reads of its triangle (object-space
// corners, vertex normals, UV0 and its area, tangents), gathered once when the tracer is built
// instead of at every hit through the index buffer from five separate vertex arrays (one cache
// line of indices and up to twelve of attributes per hit on a large scene like Sponza; a record
// is 152 bytes, three lines). Values are copied, not recomputed, so shading reads exactly the
// numbers it read before. The second UV set and vertex colours, rare, are still read from the
// mesh.
//
// A mesh whose vertices change (skinning, morph targets) must rebuild its records before the
// next trace: EmbreeScene::update_mesh_triangles.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace ddish::scene {
struct Mesh;
}

namespace ddish::trace {

struct TriangleRecord {
  enum : std::uint32_t { kNormals = 1u, kUvs = 2u, kTangents = 4u };  // what the mesh has
  glm::vec3 p[3]{};   // object-space corners
  glm::vec3 n[3]{};   // vertex normals (object space)
  glm::vec2 uv[3]{};  // UV0
  float uv_area = 0.0f;  // of UV0: uv_area(mesh, prim, 0)
  glm::vec4 t[3]{};      // glTF tangents: xyz, w handedness
  std::uint32_t flags = 0;

  bool has(std::uint32_t f) const { return (flags & f) != 0; }
  // Barycentric interpolation with vertex weights (1-u-v, u, v), as the mesh arrays were.
  template <typename T>
  static T interpolate(const T (&a)[3], float u, float v) {
    return a[0] * (1.0f - u - v) + a[1] * u + a[2] * v;
  }
};

// The records of every triangle of `mesh`, in its index order.
std::vector<TriangleRecord> make_triangle_records(const scene::Mesh& mesh);

}  // namespace ddish::trace
