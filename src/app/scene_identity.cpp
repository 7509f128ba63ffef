#include "app/scene_identity.h"

#include <cstring>

#include "scene/scene.h"

namespace ddish::app {
namespace {

class Fnv1a {
 public:
  void bytes(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) hash_ = (hash_ ^ p[i]) * 0x100000001b3ull;
  }
  template <typename T>
  void value(const T& v) {
    bytes(&v, sizeof(T));
  }
  std::uint64_t hash() const { return hash_; }

 private:
  std::uint64_t hash_ = 0xcbf29ce484222325ull;
};

}  // namespace

std::uint64_t geometry_identity(const scene::Scene& scene) {
  Fnv1a h;
  h.value(std::uint64_t(scene.meshes.size()));
  for (const scene::Mesh& m : scene.meshes) {
    h.value(std::uint64_t(m.positions.size()));
    h.bytes(m.positions.data(), m.positions.size() * sizeof(glm::vec3));
    h.value(std::uint64_t(m.indices.size()));
    h.bytes(m.indices.data(), m.indices.size() * sizeof(std::uint32_t));
  }
  h.value(std::uint64_t(scene.nodes.size()));
  for (const scene::Node& n : scene.nodes) {
    h.value(n.translation);
    h.value(n.rotation);
    h.value(n.scale);
    h.value(std::uint64_t(n.meshes.size()));
    for (int mesh : n.meshes) h.value(mesh);
  }
  return h.hash();
}

std::uint64_t scene_identity(std::uint64_t geometry, const probes::ProbeGrid& grid, int sh_order) {
  Fnv1a h;
  h.value(geometry);
  h.value(grid.counts());
  h.value(grid.bounds().min);
  h.value(grid.bounds().max);
  h.value(sh_order);
  return h.hash();
}

}  // namespace ddish::app
