#include "raster/gpu_meshes.h"

#include <cstddef>
#include <stdexcept>

#include "gpu/device.h"
#include "gpu/transfer.h"
#include "scene/scene.h"

namespace ddish::raster {

namespace {

Vertex make_vertex(const scene::Mesh& mesh, std::size_t i) {
  Vertex v{};
  const glm::vec3& p = mesh.positions[i];
  v.position[0] = p.x;
  v.position[1] = p.y;
  v.position[2] = p.z;
  // The loader guarantees positions; the other arrays are either complete or absent, and an
  // absent one reads as the neutral value (the tracer does the same).
  const glm::vec3 n = i < mesh.normals.size() ? mesh.normals[i] : glm::vec3(0.0f, 0.0f, 1.0f);
  v.normal[0] = n.x;
  v.normal[1] = n.y;
  v.normal[2] = n.z;
  const glm::vec2 uv = i < mesh.uvs.size() ? mesh.uvs[i] : glm::vec2(0.0f);
  v.uv[0] = uv.x;
  v.uv[1] = uv.y;
  const glm::vec4 t = i < mesh.tangents.size() ? mesh.tangents[i] : glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  v.tangent[0] = t.x;
  v.tangent[1] = t.y;
  v.tangent[2] = t.z;
  v.tangent[3] = t.w;
  const glm::vec2 uv1 = i < mesh.uvs1.size() ? mesh.uvs1[i] : glm::vec2(0.0f);
  v.uv1[0] = uv1.x;
  v.uv1[1] = uv1.y;
  const glm::vec4 c = i < mesh.colors.size() ? mesh.colors[i] : glm::vec4(1.0f);  // COLOR_0
  v.color[0] = c.r;
  v.color[1] = c.g;
  v.color[2] = c.b;
  v.color[3] = c.a;
  return v;
}

// A deformed mesh's clusters are culled by the mesh's bounds in its current pose: their own
// bounds and backface cones were computed for the rest pose.
void fit_to_pose(std::span<Cluster> clusters, const scene::Aabb& bounds) {
  for (Cluster& c : clusters) {
    c.min = bounds.empty() ? glm::vec3(0.0f) : bounds.min;
    c.max = bounds.empty() ? glm::vec3(0.0f) : bounds.max;
    c.cone_cutoff = 1.0f;
  }
}

}  // namespace

GpuMeshes::GpuMeshes(const gpu::Device& device, gpu::CommandRunner& runner,
                     const scene::Scene& scene) {
  std::vector<Vertex> vertices;
  std::vector<std::uint32_t> indices;
  ranges_.reserve(scene.meshes.size());
  for (const scene::Mesh& mesh : scene.meshes) {
    MeshRange range;
    range.first_index = static_cast<std::uint32_t>(indices.size());
    range.vertex_offset = static_cast<std::int32_t>(vertices.size());
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) vertices.push_back(make_vertex(mesh, i));
    ClusteredIndices clustered = cluster_mesh(mesh, range.first_index);
    range.index_count = static_cast<std::uint32_t>(clustered.indices.size());
    range.first_cluster = static_cast<std::uint32_t>(clusters_.size());
    range.cluster_count = static_cast<std::uint32_t>(clustered.clusters.size());
    indices.insert(indices.end(), clustered.indices.begin(), clustered.indices.end());
    clusters_.insert(clusters_.end(), clustered.clusters.begin(), clustered.clusters.end());
    ranges_.push_back(range);
  }
  versions_.assign(scene.meshes.size(), 0);
  for (const scene::DeformedMesh& d : scene.deformed) {
    const auto m = static_cast<std::size_t>(d.mesh);
    deformed_.push_back(d.mesh);
    versions_[m] = scene.meshes[m].pose_version;
    fit_to_pose(std::span<Cluster>(clusters_).subspan(ranges_[m].first_cluster, ranges_[m].cluster_count),
                scene.meshes[m].bounds);
  }
  // Vulkan has no empty buffers: a scene without geometry still gets one (unused) element.
  if (vertices.empty()) vertices.push_back(Vertex{});
  if (indices.empty()) indices.push_back(0);
  const VkDeviceSize vertex_bytes = vertices.size() * sizeof(Vertex);
  const VkDeviceSize index_bytes = indices.size() * sizeof(std::uint32_t);
  vertices_ = gpu::Buffer(device, vertex_bytes, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                          gpu::MemoryUse::device_local);
  indices_ = gpu::Buffer(device, index_bytes, VK_BUFFER_USAGE_INDEX_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                         gpu::MemoryUse::device_local);
  gpu::upload(device, runner, vertices_, vertices.data(), vertex_bytes);
  gpu::upload(device, runner, indices_, indices.data(), index_bytes);
}

bool GpuMeshes::update(const gpu::Device& device, gpu::CommandRunner& runner, const scene::Scene& scene) {
  bool changed = false;
  std::vector<Vertex> vertices;
  for (int mesh : deformed_) {
    const auto m = static_cast<std::size_t>(mesh);
    const scene::Mesh& posed = scene.meshes[m];
    if (posed.pose_version == versions_[m] || posed.positions.empty()) continue;
    vertices.clear();
    for (std::size_t i = 0; i < posed.positions.size(); ++i) vertices.push_back(make_vertex(posed, i));
    const MeshRange& r = ranges_[m];
    gpu::upload(device, runner, vertices_, vertices.data(), vertices.size() * sizeof(Vertex),
                static_cast<VkDeviceSize>(r.vertex_offset) * sizeof(Vertex));
    fit_to_pose(std::span<Cluster>(clusters_).subspan(r.first_cluster, r.cluster_count), posed.bounds);
    versions_[m] = posed.pose_version;
    changed = true;
  }
  return changed;
}

void GpuMeshes::bind(VkCommandBuffer cmd) const {
  const VkBuffer buffer = vertices_.handle();
  const VkDeviceSize offset = 0;
  vkCmdBindVertexBuffers(cmd, 0, 1, &buffer, &offset);
  vkCmdBindIndexBuffer(cmd, indices_.handle(), 0, VK_INDEX_TYPE_UINT32);
}

void GpuMeshes::draw(VkCommandBuffer cmd, int mesh) const {
  const MeshRange& r = range(mesh);
  if (r.index_count == 0) return;
  vkCmdDrawIndexed(cmd, r.index_count, 1, r.first_index, r.vertex_offset, 0);
}

std::span<const Cluster> GpuMeshes::clusters(int mesh) const {
  const MeshRange& r = range(mesh);
  return std::span<const Cluster>(clusters_).subspan(r.first_cluster, r.cluster_count);
}

VkVertexInputBindingDescription GpuMeshes::binding() {
  return {0, sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX};
}

std::array<VkVertexInputAttributeDescription, 6> GpuMeshes::attributes() {
  return {{{0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, position)},
           {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, normal)},
           {2, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(Vertex, uv)},
           {3, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(Vertex, tangent)},
           {4, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(Vertex, uv1)},
           {5, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(Vertex, color)}}};
}

}  // namespace ddish::raster
