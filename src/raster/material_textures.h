// Materials on the GPU: the scene's textures as sampled images with full mip chains (generated
// on the GPU by blits), one sampler per glTF wrap and filter combination, and one descriptor
// set per material (lavapipe has no descriptor indexing, so a material is bound per draw): a
// uniform block of its factors and texture transforms, and five combined image samplers (base
// colour and emissive in sRGB formats, the rest linear). Empty slots are bound to a 1x1 white texture and flagged off in the uniform block.
// Metallic-roughness textures are the exception to GPU mips: their chain is built on the CPU with
// roughness averaged for the shading it feeds (raster/roughness_mips.h).
#pragma once

#include <cstdint>
#include <map>
#include <tuple>
#include <utility>
#include <vector>

#include <vulkan/vulkan.h>

#include "gpu/buffer.h"
#include "gpu/handle.h"
#include "gpu/image.h"
#include "raster/roughness_mips.h"
#include "scene/scene.h"

namespace ddish::gpu {
class CommandRunner;
class Device;
}  // namespace ddish::gpu

namespace ddish::raster {

class MaterialTextures {
 public:
  // textures = false: no texture is uploaded or flagged (SceneFeatures had none, or the plan
  // leaves sampling out); every slot reads the white texture and the shader skips sampling.
  // anisotropy: RendererOptions::anisotropy (raster/anisotropy.h; 0 automatic, 1 off); throws
  // std::invalid_argument for a value outside 0..16.
  MaterialTextures(const gpu::Device& device, gpu::CommandRunner& runner, const scene::Scene& scene,
                   bool textures, int anisotropy = 0);

  VkDescriptorSetLayout layout() const { return layout_.get(); }
  // The set of scene material `material`; -1 is glTF's default material.
  VkDescriptorSet set(int material) const;
  std::size_t texture_images() const { return images_.size(); }
  // The sampler's maxAnisotropy as resolved for the device; 1: anisotropic filtering off.
  float max_anisotropy() const { return max_anisotropy_; }
  // For passes that pick the material per pixel (raster/visibility_pass.h): every material's
  // five slots (the sets' bindings 1..5) in set order, the default material last; and the
  // uniform blocks, also a storage buffer, one MaterialData every uniform_stride() bytes.
  const std::vector<VkDescriptorImageInfo>& slot_images() const { return slot_images_; }
  const gpu::Buffer& uniforms() const { return uniforms_; }
  VkDeviceSize uniform_stride() const { return stride_; }
  std::size_t material_count() const { return sets_.size(); }

  // A texture uploaded to an RGBA8 image of `format` with all mips (public for tests). Throws
  // GpuError naming the format feature the device lacks for mip generation.
  static gpu::Image upload_texture(const gpu::Device& device, gpu::CommandRunner& runner,
                                   const scene::Texture& texture, VkFormat format);
  // A mip chain built on the host (roughness_mip_chain's levels, level 0 first, each half the
  // one before) uploaded as one image of `format` (public for tests).
  static gpu::Image upload_mip_chain(const gpu::Device& device, gpu::CommandRunner& runner,
                                     const std::vector<MipLevel>& chain, VkFormat format);

  // How a slot's texture is stored: sRGB colour, linear data, or metallic-roughness (linear,
  // roughness mips averaged for shading); one image per texture and kind.
  enum class Kind { Srgb, Linear, MetallicRoughness };

 private:
  const gpu::Image& image_for(const gpu::Device& device, gpu::CommandRunner& runner,
                              const scene::Scene& scene, int texture, Kind kind);

  VkDevice device_ = VK_NULL_HANDLE;
  float max_anisotropy_ = 1.0f;
  gpu::Image white_;
  std::map<std::pair<int, Kind>, gpu::Image> images_;  // (texture, kind) -> image
  // The sampler for a slot's glTF wrapS / wrapT and magFilter / minFilter, made on first use.
  VkSampler sampler_for(const scene::TextureSlot& slot);

  using SamplerKey =
      std::tuple<scene::Wrap, scene::Wrap, scene::Filter, scene::Filter, scene::MipFilter>;
  std::map<SamplerKey, gpu::DeviceHandle<VkSampler, vkDestroySampler>> samplers_;
  gpu::Buffer uniforms_;
  gpu::DeviceHandle<VkDescriptorSetLayout, vkDestroyDescriptorSetLayout> layout_;
  gpu::DeviceHandle<VkDescriptorPool, vkDestroyDescriptorPool> pool_;
  std::vector<VkDescriptorSet> sets_;  // scene materials, then the default material
  std::vector<VkDescriptorImageInfo> slot_images_;
  VkDeviceSize stride_ = 0;
};

}  // namespace ddish::raster
