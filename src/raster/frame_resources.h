// Descriptor set 0 of every rasterizer pipeline: what all draws of a frame share. Frame
// constants (environment, counts), the views, the punctual lights, the shadow layers' matrices,
// the shadow-map array with a comparison sampler, and the specular-layer albedo table the
// diffuse BSDF needs (trace::DielectricSpecularAlbedo's nodes, so that both renderers read the
// same numbers). Buffers are host-visible and rewritten each frame; the renderer runs one frame
// at a time, so the GPU never reads a buffer while it is written.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <vulkan/vulkan.h>

#include "gpu/buffer.h"
#include "gpu/handle.h"
#include "raster/gpu_types.h"

namespace ddish::gpu {
class Device;
}

namespace ddish::raster {

class FrameResources {
 public:
  static constexpr std::uint32_t kMaxViews = 64;

  FrameResources(const gpu::Device& device, std::uint32_t max_lights, std::uint32_t max_layers);

  VkDescriptorSetLayout layout() const { return layout_.get(); }
  VkDescriptorSet set() const { return set_; }

  // Writes this frame's data. Throws GpuError when there are more views, lights or layers than
  // the buffers were made for.
  void update(const FrameData& frame, std::span<const ViewData> views,
              std::span<const LightData> lights, std::span<const ShadowLayerData> layers);
  // Points binding 4 at the shadow-map array (a depth view in SHADER_READ_ONLY layout).
  void bind_shadow_maps(VkImageView view, VkSampler sampler);

  // The albedo table as uploaded, in vec4 cells that each hold what one bilinear step reads
  // (one per-lane load instead of four on lavapipe): for roughness node r (32) and cosine cell c
  // (31), (E, dE/dF0) at nodes c and c + 1; then for roughness cell r (31) (E_avg, dE_avg/dF0) at
  // nodes r and r + 1 (trace::DielectricSpecularAlbedo::Slice::slope is dE/dF0).
  static std::vector<float> albedo_table();

 private:
  VkDevice device_ = VK_NULL_HANDLE;
  std::uint32_t max_lights_ = 0;
  std::uint32_t max_layers_ = 0;
  gpu::Buffer frame_;
  gpu::Buffer views_;
  gpu::Buffer lights_;
  gpu::Buffer layers_;
  gpu::Buffer albedo_;
  gpu::DeviceHandle<VkDescriptorSetLayout, vkDestroyDescriptorSetLayout> layout_;
  gpu::DeviceHandle<VkDescriptorPool, vkDestroyDescriptorPool> pool_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
};

}  // namespace ddish::raster
