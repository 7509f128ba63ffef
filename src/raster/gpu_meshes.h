// Scene geometry on the GPU: every mesh's vertices and indices packed into one vertex buffer and
// one index buffer, uploaded once. Instances share their mesh's range and differ only in the
// transform pushed with each draw, so a moving instance costs nothing to re-upload. A deformed
// mesh (skin, morph targets) has its range re-uploaded from the posed arrays whenever its pose
// changes (update), so the rasterizer draws the pose the tracer traces. Each mesh's
// indices are stored in cluster order (raster/clusters.h) so views can draw visible clusters only.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <vulkan/vulkan.h>

#include "gpu/buffer.h"
#include "raster/clusters.h"

namespace ddish::gpu {
class CommandRunner;
class Device;
}  // namespace ddish::gpu

namespace ddish::scene {
struct Scene;
}

namespace ddish::raster {

// One interleaved vertex: 72 bytes. Attribute locations 0..5 in forward_vertex.glsl (position,
// normal, UV0, tangent, UV1, COLOR_0); the shadow pass reads the position only, the masked
// shadow pass the UVs and the colour's alpha.
struct Vertex {
  float position[3];
  float normal[3];
  float uv[2];
  float tangent[4];
  float uv1[2];
  float color[4];  // COLOR_0, linear RGBA; white without vertex colours
};
static_assert(sizeof(Vertex) == 72);

struct MeshRange {
  std::uint32_t first_index = 0;
  std::uint32_t index_count = 0;
  std::int32_t vertex_offset = 0;
  std::uint32_t first_cluster = 0;  // into GpuMeshes::clusters()
  std::uint32_t cluster_count = 0;
};

class GpuMeshes {
 public:
  GpuMeshes(const gpu::Device& device, gpu::CommandRunner& runner, const scene::Scene& scene);

  // Re-uploads the vertices of every deformed mesh whose scene::Mesh::pose_version changed since
  // its last upload and fits its clusters to the new pose. Returns whether any changed. Work
  // that reads the buffers must not be in flight.
  bool update(const gpu::Device& device, gpu::CommandRunner& runner, const scene::Scene& scene);

  // Binds the vertex buffer (binding 0) and the index buffer for the draws that follow.
  void bind(VkCommandBuffer cmd) const;
  // Records the draw of mesh `mesh` (its whole index range); nothing for an empty mesh.
  void draw(VkCommandBuffer cmd, int mesh) const;

  std::span<const Cluster> clusters(int mesh) const;
  std::size_t cluster_total() const { return clusters_.size(); }

  const MeshRange& range(int mesh) const { return ranges_.at(static_cast<std::size_t>(mesh)); }
  std::size_t mesh_count() const { return ranges_.size(); }
  // The buffers themselves, also storage buffers: the visibility pass reads the triangles of
  // the pixels it shades from them (raster/visibility_pass.h).
  const gpu::Buffer& vertex_buffer() const { return vertices_; }
  const gpu::Buffer& index_buffer() const { return indices_; }

  // Vertex input of the pipelines that draw these buffers: all six attributes, or the
  // position alone (depth-only passes).
  static VkVertexInputBindingDescription binding();
  static std::array<VkVertexInputAttributeDescription, 6> attributes();

 private:
  gpu::Buffer vertices_;
  gpu::Buffer indices_;
  std::vector<MeshRange> ranges_;
  std::vector<Cluster> clusters_;
  std::vector<int> deformed_;              // the scene's deformed meshes
  std::vector<std::uint64_t> versions_;    // per mesh: the pose_version on the GPU
};

}  // namespace ddish::raster
