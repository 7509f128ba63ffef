// The BRDF lookup tables of the rasterizer's indirect light, computed by the project itself and
// uploaded once, in one descriptor set (set 2 by default, BRDF_SET in
// shaders/include/probe_lighting.glsl, which reads them):
//   binding 0  sampler2D brdf_dfg_table: RG16F, the split-sum DFG (scale, bias) of brdf_dfg.h
//              over (cbrt(n.v), roughness), size x size nodes at texel centres (32 x 32)
//   binding 1  uniform BrdfGgxZhBlock: sh::ggx_zh_table(), 65 vec4 of bands 1..4 (std140)
// The diffuse term's view-dependent scale 1 - E(n.v) is not here: the forward shader reads it
// from the tracer's own albedo table in the frame set (raster/frame_resources.h), which its
// direct light needs anyway.
// All are visible to every stage; the samplers filter linearly and clamp to the edge.
#pragma once

#include <cstdint>

#include <vulkan/vulkan.h>

#include "gpu/buffer.h"
#include "gpu/image.h"
#include "raster/brdf_dfg.h"
#include "raster/probe_descriptor_set.h"

namespace ddish::gpu {
class CommandRunner;
class Device;
}  // namespace ddish::gpu

namespace ddish::raster {

class BrdfTables {
 public:
  static constexpr std::uint32_t kDfgBinding = 0;
  static constexpr std::uint32_t kGgxZhBinding = 1;

  // Computes the DFG table (compute_dfg_table() at its defaults), builds the ZH table from
  // sh::ggx_zh_table(), uploads both and waits.
  BrdfTables(const gpu::Device& device, gpu::CommandRunner& runner);
  // The same with a DFG table computed (or cached) by the caller.
  BrdfTables(const gpu::Device& device, gpu::CommandRunner& runner, DfgTable dfg);

  const DfgTable& dfg() const { return dfg_; }
  // CPU time spent computing the DFG table in the constructor (0 when it was given).
  double dfg_compute_ms() const { return dfg_ms_; }

  VkDescriptorSetLayout layout() const { return descriptors_.layout(); }
  VkDescriptorSet set() const { return descriptors_.set(); }

 private:
  void create(const gpu::Device& device, gpu::CommandRunner& runner);

  DfgTable dfg_;
  double dfg_ms_ = 0.0;
  gpu::Image dfg_image_;
  gpu::Buffer ggx_zh_buffer_;
  Sampler sampler_;
  OwnedDescriptorSet descriptors_;
};

}  // namespace ddish::raster
