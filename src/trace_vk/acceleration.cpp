#include "trace_vk/acceleration.h"

#include <algorithm>

#include "gpu/commands.h"
#include "gpu/device.h"
#include "gpu/error.h"
#include "trace_vk/scene_layout.h"

namespace ddish::trace_vk {

namespace {

constexpr VkBufferUsageFlags kAddressed = VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;

VkDeviceSize align_up(VkDeviceSize v, VkDeviceSize a) { return (v + a - 1) / a * a; }

VkDeviceSize scratch_alignment(const gpu::Device& device) {
  VkPhysicalDeviceAccelerationStructurePropertiesKHR as{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_PROPERTIES_KHR};
  VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  props.pNext = &as;
  vkGetPhysicalDeviceProperties2(device.physical(), &props);
  return std::max<VkDeviceSize>(as.minAccelerationStructureScratchOffsetAlignment, 1);
}

// Builds written by one command are read (by traces or a later build) only after this.
void build_barrier(VkCommandBuffer cmd) {
  gpu::memory_barrier(cmd, VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
                      VK_ACCESS_ACCELERATION_STRUCTURE_WRITE_BIT_KHR, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                      VK_ACCESS_ACCELERATION_STRUCTURE_READ_BIT_KHR | VK_ACCESS_ACCELERATION_STRUCTURE_WRITE_BIT_KHR);
}

VkAccelerationStructureInstanceKHR to_vk_instance(const GpuInstance& g, std::uint32_t index, VkDeviceAddress blas) {
  VkAccelerationStructureInstanceKHR v{};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) v.transform.matrix[r][c] = g.object_to_world[c][r];
  v.instanceCustomIndex = index;  // the shaders' instance index
  v.mask = blas ? 0xFFu : 0u;     // a mesh without triangles is never hit
  v.instanceShaderBindingTableRecordOffset = 0;
  // Back faces are hit too: the integrator sees them (absorbing, counted for classification).
  v.flags = VK_GEOMETRY_INSTANCE_TRIANGLE_FACING_CULL_DISABLE_BIT_KHR;
  v.accelerationStructureReference = blas;
  return v;
}

// A deformed mesh's bottom level is refitted when it changes pose (built with ALLOW_UPDATE).
// Measured on lavapipe (Mesa 25), a 147k-triangle mesh: a refit 10.5-13 ms against 12-21 ms for a
// rebuild (medians of 6 poses, two alternating runs of each, load 3.6-3.8), and no measurable
// change in the rays/s traced after it.
VkBuildAccelerationStructureFlagsKHR blas_flags(bool deformed) {
  return VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR |
         (deformed ? VK_BUILD_ACCELERATION_STRUCTURE_ALLOW_UPDATE_BIT_KHR : 0);
}

}  // namespace

AccelerationStructure::AccelerationStructure(const gpu::Device& device, const RtFunctions& rt,
                                             VkAccelerationStructureTypeKHR type, VkDeviceSize size)
    : device_(device.handle()),
      rt_(rt),
      storage_(device, size, VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_STORAGE_BIT_KHR | kAddressed,
               gpu::MemoryUse::device_local) {
  VkAccelerationStructureCreateInfoKHR info{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_CREATE_INFO_KHR};
  info.buffer = storage_.handle();
  info.size = size;
  info.type = type;
  gpu::check(rt_.create_acceleration_structure(device_, &info, nullptr, &handle_),
             "vkCreateAccelerationStructureKHR");
  VkAccelerationStructureDeviceAddressInfoKHR address{
      VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_DEVICE_ADDRESS_INFO_KHR};
  address.accelerationStructure = handle_;
  address_ = rt_.get_address(device_, &address);
}

AccelerationStructure::~AccelerationStructure() {
  rt_.destroy_acceleration_structure(device_, handle_, nullptr);
}

SceneAcceleration::SceneAcceleration(const gpu::Device& device, const RtFunctions& rt,
                                     gpu::CommandRunner& runner, const gpu::Buffer& vertices,
                                     const gpu::Buffer& indices, const std::vector<GpuMesh>& meshes,
                                     const std::vector<GpuMaterial>& materials,
                                     const std::vector<GpuInstance>& instances, const std::vector<bool>& deformed)
    : device_(device), rt_(rt) {
  const VkDeviceSize alignment = scratch_alignment(device);
  const auto total_vertices = static_cast<std::uint32_t>(vertices.size() / sizeof(GpuVertex));
  std::vector<VkAccelerationStructureGeometryKHR>& geometries = geometries_;
  geometries.resize(meshes.size());
  triangle_counts_.assign(meshes.size(), 0);
  refit_offsets_.assign(meshes.size(), 0);
  VkDeviceSize refit_bytes = 0;
  std::vector<VkAccelerationStructureBuildGeometryInfoKHR> builds;
  std::vector<VkAccelerationStructureBuildRangeInfoKHR> ranges;
  std::vector<VkDeviceSize> scratch_offsets;
  VkDeviceSize scratch_bytes = 0;
  blas_.resize(meshes.size());
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    const GpuMesh& mesh = meshes[m];
    if (mesh.triangle_count == 0) continue;
    const std::uint32_t vertex_end = m + 1 < meshes.size() ? meshes[m + 1].first_vertex : total_vertices;
    VkAccelerationStructureGeometryKHR& g = geometries[m];
    g = {VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
    g.geometryType = VK_GEOMETRY_TYPE_TRIANGLES_KHR;
    const bool alpha = (materials[mesh.material].flags & (kMaterialMask | kMaterialBlend)) != 0;
    g.flags = alpha ? VkGeometryFlagsKHR(0) : VkGeometryFlagsKHR(VK_GEOMETRY_OPAQUE_BIT_KHR);
    VkAccelerationStructureGeometryTrianglesDataKHR& t = g.geometry.triangles;
    t = {VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_TRIANGLES_DATA_KHR};
    t.vertexFormat = VK_FORMAT_R32G32B32_SFLOAT;
    t.vertexData.deviceAddress = vertices.device_address() + VkDeviceSize(mesh.first_vertex) * sizeof(GpuVertex);
    t.vertexStride = sizeof(GpuVertex);
    t.maxVertex = vertex_end - mesh.first_vertex - 1;
    t.indexType = VK_INDEX_TYPE_UINT32;
    t.indexData.deviceAddress = indices.device_address() + VkDeviceSize(mesh.first_index) * sizeof(std::uint32_t);

    VkAccelerationStructureBuildGeometryInfoKHR build{
        VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR};
    build.type = VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR;
    const bool deforms = m < deformed.size() && deformed[m];
    build.flags = blas_flags(deforms);
    build.mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR;
    build.geometryCount = 1;
    build.pGeometries = &g;
    VkAccelerationStructureBuildSizesInfoKHR sizes{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
    rt_.get_build_sizes(device.handle(), VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR, &build,
                        &mesh.triangle_count, &sizes);
    triangle_counts_[m] = mesh.triangle_count;
    if (deforms) {
      refit_offsets_[m] = refit_bytes;
      refit_bytes = align_up(refit_bytes + sizes.updateScratchSize, alignment);
    }
    blas_[m] = std::make_unique<AccelerationStructure>(device, rt_, VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR,
                                                       sizes.accelerationStructureSize);
    build.dstAccelerationStructure = blas_[m]->handle();
    builds.push_back(build);
    ranges.push_back({mesh.triangle_count, 0, 0, 0});
    scratch_offsets.push_back(scratch_bytes);
    scratch_bytes = align_up(scratch_bytes + sizes.buildScratchSize, alignment);
  }
  if (!builds.empty()) {
    // One scratch buffer, each build in its own aligned range, so all build in one command.
    gpu::Buffer scratch(device, scratch_bytes + alignment, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | kAddressed,
                        gpu::MemoryUse::device_local);
    const VkDeviceAddress base = align_up(scratch.device_address(), alignment);
    for (std::size_t b = 0; b < builds.size(); ++b) builds[b].scratchData.deviceAddress = base + scratch_offsets[b];
    std::vector<const VkAccelerationStructureBuildRangeInfoKHR*> range_ptrs;
    for (const auto& r : ranges) range_ptrs.push_back(&r);
    runner.run([&](VkCommandBuffer cmd) {
      rt_.cmd_build(cmd, static_cast<std::uint32_t>(builds.size()), builds.data(), range_ptrs.data());
      build_barrier(cmd);
    });
  }
  if (std::find(deformed.begin(), deformed.end(), true) != deformed.end())
    refit_scratch_ = std::make_unique<gpu::Buffer>(device, refit_bytes + alignment,
                                                     VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | kAddressed,
                                                     gpu::MemoryUse::device_local);
  build_tlas(runner, instances);
}

void SceneAcceleration::refit(gpu::CommandRunner& runner, const std::vector<std::uint32_t>& meshes) {
  std::vector<VkAccelerationStructureBuildGeometryInfoKHR> builds;
  std::vector<VkAccelerationStructureBuildRangeInfoKHR> ranges;
  const VkDeviceAddress base =
      refit_scratch_ ? align_up(refit_scratch_->device_address(), scratch_alignment(device_)) : 0;
  for (std::uint32_t m : meshes) {
    if (m >= blas_.size() || !blas_[m] || !refit_scratch_) continue;
    VkAccelerationStructureBuildGeometryInfoKHR build{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR};
    build.type = VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR;
    build.flags = blas_flags(true);
    build.mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_UPDATE_KHR;
    build.srcAccelerationStructure = blas_[m]->handle();  // in place
    build.dstAccelerationStructure = blas_[m]->handle();
    build.geometryCount = 1;
    build.pGeometries = &geometries_[m];
    build.scratchData.deviceAddress = base + refit_offsets_[m];
    builds.push_back(build);
    ranges.push_back({triangle_counts_[m], 0, 0, 0});
  }
  if (builds.empty()) return;
  std::vector<const VkAccelerationStructureBuildRangeInfoKHR*> range_ptrs;
  for (const auto& r : ranges) range_ptrs.push_back(&r);
  runner.run([&](VkCommandBuffer cmd) {
    // The vertex upload and the last trace that read the old structures come first.
    gpu::memory_barrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT,
                        VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
                        VK_ACCESS_ACCELERATION_STRUCTURE_READ_BIT_KHR | VK_ACCESS_ACCELERATION_STRUCTURE_WRITE_BIT_KHR |
                            VK_ACCESS_SHADER_READ_BIT);
    rt_.cmd_build(cmd, static_cast<std::uint32_t>(builds.size()), builds.data(), range_ptrs.data());
    build_barrier(cmd);
  });
}

void SceneAcceleration::update(gpu::CommandRunner& runner, const std::vector<GpuInstance>& instances) {
  build_tlas(runner, instances);
}

void SceneAcceleration::build_tlas(gpu::CommandRunner& runner, const std::vector<GpuInstance>& instances) {
  std::vector<VkAccelerationStructureInstanceKHR> vk(instances.size());
  for (std::size_t i = 0; i < instances.size(); ++i) {
    const std::size_t m = instances[i].mesh;
    const VkDeviceAddress blas = m < blas_.size() && blas_[m] ? blas_[m]->address() : 0;
    vk[i] = to_vk_instance(instances[i], static_cast<std::uint32_t>(i), blas);
  }
  const auto count = static_cast<std::uint32_t>(vk.size());
  VkAccelerationStructureGeometryKHR g{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
  g.geometryType = VK_GEOMETRY_TYPE_INSTANCES_KHR;
  g.geometry.instances = {VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_INSTANCES_DATA_KHR};
  VkAccelerationStructureBuildGeometryInfoKHR build{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR};
  build.type = VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR;
  build.flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR;
  build.mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR;
  build.geometryCount = 1;
  build.pGeometries = &g;

  if (!tlas_ || count > tlas_capacity_) {
    tlas_capacity_ = std::max(count, 1u);
    VkAccelerationStructureBuildSizesInfoKHR sizes{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
    rt_.get_build_sizes(device_.handle(), VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR, &build, &tlas_capacity_,
                        &sizes);
    const VkDeviceSize alignment = scratch_alignment(device_);
    tlas_ = std::make_unique<AccelerationStructure>(device_, rt_, VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR,
                                                    sizes.accelerationStructureSize);
    tlas_scratch_ = std::make_unique<gpu::Buffer>(device_, sizes.buildScratchSize + alignment,
                                                  VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | kAddressed,
                                                  gpu::MemoryUse::device_local);
    instance_buffer_ = std::make_unique<gpu::Buffer>(
        device_, sizeof(VkAccelerationStructureInstanceKHR) * tlas_capacity_,
        VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR | kAddressed, gpu::MemoryUse::upload);
  }
  if (count > 0) instance_buffer_->write(vk.data(), vk.size() * sizeof(vk[0]));
  g.geometry.instances.data.deviceAddress = instance_buffer_->device_address();
  build.dstAccelerationStructure = tlas_->handle();
  build.scratchData.deviceAddress = align_up(tlas_scratch_->device_address(), scratch_alignment(device_));
  const VkAccelerationStructureBuildRangeInfoKHR range{count, 0, 0, 0};
  const VkAccelerationStructureBuildRangeInfoKHR* range_ptr = &range;
  runner.run([&](VkCommandBuffer cmd) {
    // The last trace (or build) that read the old TLAS comes before this rebuild.
    gpu::memory_barrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT,
                        VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
                        VK_ACCESS_ACCELERATION_STRUCTURE_READ_BIT_KHR | VK_ACCESS_ACCELERATION_STRUCTURE_WRITE_BIT_KHR);
    rt_.cmd_build(cmd, 1, &build, &range_ptr);
    build_barrier(cmd);
  });
}

}  // namespace ddish::trace_vk
