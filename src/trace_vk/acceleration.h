// The GPU probe tracer's acceleration structures: one bottom-level structure per mesh (object
// space, built once from the mesh's spatially sorted triangles, scene_layout.h) and a top-level
// structure of the instances, rebuilt when instances move (a rigid move changes only the
// instance transforms, so no BLAS is rebuilt; a TLAS rebuild of a few hundred instances is
// cheaper than tracking what a refit would allow). A deformed mesh (skin, morph targets) gets
// its posed vertices written into the same vertex range and its BLAS refitted in place.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <vulkan/vulkan.h>

#include "gpu/buffer.h"
#include "trace_vk/rt_functions.h"

namespace ddish::gpu {
class CommandRunner;
class Device;
}  // namespace ddish::gpu

namespace ddish::trace_vk {

struct GpuInstance;
struct GpuMaterial;
struct GpuMesh;

// An acceleration structure with its storage.
class AccelerationStructure {
 public:
  AccelerationStructure(const gpu::Device& device, const RtFunctions& rt,
                        VkAccelerationStructureTypeKHR type, VkDeviceSize size);
  ~AccelerationStructure();
  AccelerationStructure(const AccelerationStructure&) = delete;
  AccelerationStructure& operator=(const AccelerationStructure&) = delete;

  VkAccelerationStructureKHR handle() const { return handle_; }
  VkDeviceAddress address() const { return address_; }

 private:
  VkDevice device_;
  const RtFunctions& rt_;
  gpu::Buffer storage_;
  VkAccelerationStructureKHR handle_ = VK_NULL_HANDLE;
  VkDeviceAddress address_ = 0;
};

class SceneAcceleration {
 public:
  // vertices and indices: the scene layout's buffers (made with build-input and device-address
  // usage, never reallocated: the structures keep their addresses); meshes, materials,
  // instances and the deformed meshes as in the layout. A mesh whose material is MASK or BLEND
  // is not opaque (its any-hit shaders run). Builds everything and waits.
  SceneAcceleration(const gpu::Device& device, const RtFunctions& rt, gpu::CommandRunner& runner,
                    const gpu::Buffer& vertices, const gpu::Buffer& indices, const std::vector<GpuMesh>& meshes,
                    const std::vector<GpuMaterial>& materials, const std::vector<GpuInstance>& instances,
                    const std::vector<bool>& deformed);

  // Refits the bottom level of deformed meshes whose vertices were rewritten (in place, in the
  // vertex buffer). The top level must be rebuilt after (update()).
  void refit(gpu::CommandRunner& runner, const std::vector<std::uint32_t>& meshes);

  // Rebuilds the top level for moved instances (the same instances, new transforms) or reshaped
  // meshes.
  void update(gpu::CommandRunner& runner, const std::vector<GpuInstance>& instances);

  VkAccelerationStructureKHR tlas() const { return tlas_->handle(); }

 private:
  void build_tlas(gpu::CommandRunner& runner, const std::vector<GpuInstance>& instances);

  const gpu::Device& device_;
  const RtFunctions& rt_;
  std::vector<std::unique_ptr<AccelerationStructure>> blas_;  // per mesh; null: no triangles
  // What a deformed mesh's bottom level is built from again (per mesh; unused for the others),
  // and one scratch buffer with an aligned range for each.
  std::vector<VkAccelerationStructureGeometryKHR> geometries_;
  std::vector<std::uint32_t> triangle_counts_;
  std::vector<VkDeviceSize> refit_offsets_;
  std::unique_ptr<gpu::Buffer> refit_scratch_;
  std::unique_ptr<AccelerationStructure> tlas_;
  std::unique_ptr<gpu::Buffer> instance_buffer_;
  std::unique_ptr<gpu::Buffer> tlas_scratch_;
  std::uint32_t tlas_capacity_ = 0;  // instances the TLAS was sized for
};

}  // namespace ddish::trace_vk
