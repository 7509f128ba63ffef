// A descriptor set that owns its layout and pool, and the linear clamp-to-edge sampler, shared
// by ProbeTextures and BrdfTables: each exposes one set that a pipeline layout names at a fixed
// set number (PROBE_SET, BRDF_SET in probe_lighting.glsl) and binds as it is. The layout, pool
// and allocation steps are also free functions, for FrameResources and MaterialTextures.
#pragma once

#include <cstdint>
#include <span>

#include <vulkan/vulkan.h>

#include "gpu/handle.h"

namespace ddish::raster {

using DescriptorSetLayout = gpu::DeviceHandle<VkDescriptorSetLayout, vkDestroyDescriptorSetLayout>;
using DescriptorPool = gpu::DeviceHandle<VkDescriptorPool, vkDestroyDescriptorPool>;

// The layout of `bindings`. Throws gpu::GpuError when vkCreateDescriptorSetLayout fails.
DescriptorSetLayout make_descriptor_set_layout(VkDevice device,
                                               std::span<const VkDescriptorSetLayoutBinding> bindings);
// A pool of at most `max_sets` sets holding `sizes` descriptors in all. Throws gpu::GpuError.
DescriptorPool make_descriptor_pool(VkDevice device, std::span<const VkDescriptorPoolSize> sizes,
                                    std::uint32_t max_sets);
// One set from `pool` per entry of `layouts`, written to `sets` (as many). Throws gpu::GpuError.
void allocate_descriptor_sets(VkDevice device, VkDescriptorPool pool,
                              std::span<const VkDescriptorSetLayout> layouts, VkDescriptorSet* sets);

class OwnedDescriptorSet {
 public:
  OwnedDescriptorSet() = default;
  // Creates the layout of `bindings`, a pool that fits exactly one such set, and the set.
  // Throws gpu::GpuError when a Vulkan call fails.
  OwnedDescriptorSet(VkDevice device, std::span<const VkDescriptorSetLayoutBinding> bindings);

  VkDescriptorSetLayout layout() const { return layout_.get(); }
  VkDescriptorSet set() const { return set_; }

  // Points `binding` (array elements from 0) at the buffer or the images.
  void write_uniform_buffer(std::uint32_t binding, const VkDescriptorBufferInfo& buffer) const;
  void write_storage_buffer(std::uint32_t binding, const VkDescriptorBufferInfo& buffer) const;
  void write_images(std::uint32_t binding, std::span<const VkDescriptorImageInfo> images) const;

 private:
  VkDevice device_ = VK_NULL_HANDLE;
  DescriptorSetLayout layout_;
  DescriptorPool pool_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;  // freed with the pool
};

using Sampler = gpu::DeviceHandle<VkSampler, vkDestroySampler>;

// Bilinear/trilinear filtering, one mip level, coordinates clamped to the edge texels: what
// the node-aligned tables and the probe textures need (no wrap-around between grid ends).
Sampler make_linear_clamp_sampler(VkDevice device);

}  // namespace ddish::raster
