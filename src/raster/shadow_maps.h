// The shadow-map pass: one D32 2D-array image holding every layer of every light (cascades,
// spot maps, cube faces; see shadow_layout.h), rendered depth-only each frame the scene has
// shadowed lights, and sampled by the forward pass through a comparison sampler (hardware PCF
// where the device filters depth linearly). Alpha-masked materials get a second pipeline that
// discards below their cutoff, so a leaf casts the shadow of a leaf, not of its quad; blended
// ones go through it too, dithered to cover a fraction alpha of the map. A frame
// without layers records nothing: the count of passes recorded is kept so that tests can check
// a light-less scene pays for none.
#pragma once

#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

#include "gpu/handle.h"
#include "gpu/image.h"
#include "raster/graphics_pipeline.h"

namespace ddish::gpu {
class CommandRunner;
class Device;
}  // namespace ddish::gpu

namespace ddish::scene {
struct Scene;
}

namespace ddish::raster {

class GpuMeshes;
class MaterialTextures;

class ShadowMaps {
 public:
  static constexpr VkFormat kFormat = VK_FORMAT_D32_SFLOAT;

  // capacity: the most layers a frame will render (at least one layer is allocated so the
  // forward pass always has an image to bind). frame_layout: set 0's layout; material_layout:
  // MaterialTextures' layout, used as set 1 by the masked pipeline, which is only built when
  // alpha_test is true (the scene has masked or blended materials).
  ShadowMaps(const gpu::Device& device, gpu::CommandRunner& runner, std::uint32_t map_size,
             std::uint32_t capacity, VkDescriptorSetLayout frame_layout,
             VkDescriptorSetLayout material_layout, bool alpha_test);

  // Records `layers` depth passes (layer i with shadow_layers[i]'s matrix, every instance of
  // the scene) and leaves the image ready for sampling. frame_set is bound as set 0.
  void record(VkCommandBuffer cmd, const scene::Scene& scene, const GpuMeshes& meshes,
              const MaterialTextures& materials, VkDescriptorSet frame_set, std::uint32_t layers);

  VkImageView view() const { return array_view_.get(); }  // every layer, as a 2D array
  VkSampler sampler() const { return sampler_.get(); }
  std::uint32_t map_size() const { return map_size_; }
  // Whether the sampler filters the comparisons bilinearly (the format's linear filtering).
  bool filters_linearly() const { return linear_; }
  std::uint32_t capacity() const { return image_.desc().layers; }
  // Depth passes recorded by the last record() call.
  std::uint32_t passes_recorded() const { return passes_; }

 private:
  std::uint32_t map_size_;
  bool linear_ = false;
  gpu::Image image_;
  std::vector<gpu::ImageView> layer_views_;
  gpu::ImageView array_view_;
  gpu::DeviceHandle<VkSampler, vkDestroySampler> sampler_;
  PipelineLayout layout_;  // set 0 (frame) and set 1 (material): shared by both pipelines
  Pipeline pipeline_;
  Pipeline masked_pipeline_;  // only with alpha_test
  std::uint32_t passes_ = 0;
};

}  // namespace ddish::raster
