#include "raster/material_textures.h"

#include <algorithm>
#include <array>
#include <bit>
#include <stdexcept>
#include <string>

#include "gpu/commands.h"
#include "gpu/device.h"
#include "gpu/error.h"
#include "raster/anisotropy.h"
#include "raster/gpu_types.h"
#include "raster/probe_descriptor_set.h"
#include "scene/scene.h"

namespace ddish::raster {

namespace {

constexpr std::uint32_t kSlots = kMaterialSlots;  // bindings 1..5, in forward_main.glsl's order

void mip_barrier(VkCommandBuffer cmd, VkImage image, std::uint32_t mip, VkImageLayout from,
                 VkImageLayout to, VkAccessFlags src, VkAccessFlags dst, VkPipelineStageFlags dst_stage) {
  VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  b.srcAccessMask = src;
  b.dstAccessMask = dst;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, mip, 1, 0, 1};
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, dst_stage, 0, 0, nullptr, 0, nullptr, 1, &b);
}

void require_blit_features(const gpu::Device& device, VkFormat format) {
  VkFormatProperties props{};
  vkGetPhysicalDeviceFormatProperties(device.physical(), format, &props);
  const VkFormatFeatureFlags need = VK_FORMAT_FEATURE_BLIT_SRC_BIT | VK_FORMAT_FEATURE_BLIT_DST_BIT |
                                    VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
  if ((props.optimalTilingFeatures & need) != need)
    throw gpu::GpuError(device.info().name + " cannot blit and linearly filter VkFormat " +
                        std::to_string(static_cast<int>(format)) +
                        " (needed to build texture mipmaps)");
}

}  // namespace

gpu::Image MaterialTextures::upload_texture(const gpu::Device& device, gpu::CommandRunner& runner,
                                            const scene::Texture& texture, VkFormat format) {
  require_blit_features(device, format);
  const auto w = static_cast<std::uint32_t>(std::max(texture.width, 1));
  const auto h = static_cast<std::uint32_t>(std::max(texture.height, 1));
  const std::uint32_t mips = std::bit_width(std::max(w, h));
  gpu::Image image(device, {.width = w, .height = h, .format = format,
                            .usage = VK_IMAGE_USAGE_SAMPLED_BIT, .mip_levels = mips});
  const VkDeviceSize bytes = VkDeviceSize{w} * h * 4;
  gpu::Buffer staging(device, bytes, 0, gpu::MemoryUse::upload);
  if (texture.rgba8.size() >= bytes)
    staging.write(texture.rgba8.data(), bytes);
  else  // a texture that failed to decode reads as white, as the tracer's lookup does
    std::fill_n(static_cast<std::uint8_t*>(staging.mapped()), bytes, std::uint8_t{255});

  const VkImage img = image.handle();
  runner.run([&](VkCommandBuffer cmd) {
    gpu::image_barrier(cmd, image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                       VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_ACCESS_TRANSFER_WRITE_BIT);
    VkBufferImageCopy copy{};
    copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    copy.imageExtent = {w, h, 1};
    vkCmdCopyBufferToImage(cmd, staging.handle(), img, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
    // Each level is a box-filtered blit of the one above; a level becomes a blit source (and,
    // once read, shader-readable) right after it is written.
    std::int32_t mw = static_cast<std::int32_t>(w), mh = static_cast<std::int32_t>(h);
    for (std::uint32_t m = 1; m < mips; ++m) {
      mip_barrier(cmd, img, m - 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                  VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_ACCESS_TRANSFER_WRITE_BIT,
                  VK_ACCESS_TRANSFER_READ_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
      VkImageBlit blit{};
      blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, m - 1, 0, 1};
      blit.srcOffsets[1] = {mw, mh, 1};
      mw = std::max(mw / 2, 1);
      mh = std::max(mh / 2, 1);
      blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, m, 0, 1};
      blit.dstOffsets[1] = {mw, mh, 1};
      vkCmdBlitImage(cmd, img, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, img,
                     VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_LINEAR);
      mip_barrier(cmd, img, m - 1, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                  VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_ACCESS_TRANSFER_READ_BIT,
                  VK_ACCESS_SHADER_READ_BIT, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT);
    }
    mip_barrier(cmd, img, mips - 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_ACCESS_TRANSFER_WRITE_BIT,
                VK_ACCESS_SHADER_READ_BIT, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT);
  });
  return image;
}

gpu::Image MaterialTextures::upload_mip_chain(const gpu::Device& device, gpu::CommandRunner& runner,
                                              const std::vector<MipLevel>& chain, VkFormat format) {
  if (chain.empty()) throw std::invalid_argument("a mip chain needs at least one level");
  const std::uint32_t w = chain.front().width, h = chain.front().height;
  const auto mips = static_cast<std::uint32_t>(chain.size());
  gpu::Image image(device, {.width = w, .height = h, .format = format,
                            .usage = VK_IMAGE_USAGE_SAMPLED_BIT, .mip_levels = mips});
  VkDeviceSize bytes = 0;
  std::vector<VkBufferImageCopy> copies(mips);
  for (std::uint32_t m = 0; m < mips; ++m) {
    const MipLevel& level = chain[m];
    if (level.width != std::max(w >> m, 1u) || level.height != std::max(h >> m, 1u) ||
        level.rgba8.size() != std::size_t{level.width} * level.height * 4)
      throw std::invalid_argument("mip level " + std::to_string(m) + " is not half the level above");
    copies[m].bufferOffset = bytes;
    copies[m].imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, m, 0, 1};
    copies[m].imageExtent = {level.width, level.height, 1};
    bytes += level.rgba8.size();
  }
  gpu::Buffer staging(device, bytes, 0, gpu::MemoryUse::upload);
  for (std::uint32_t m = 0; m < mips; ++m)
    staging.write(chain[m].rgba8.data(), chain[m].rgba8.size(), copies[m].bufferOffset);
  runner.run([&](VkCommandBuffer cmd) {
    gpu::image_barrier(cmd, image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                       VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_ACCESS_TRANSFER_WRITE_BIT);
    vkCmdCopyBufferToImage(cmd, staging.handle(), image.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                           mips, copies.data());
    gpu::image_barrier(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                       VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                       VK_ACCESS_SHADER_READ_BIT);
  });
  return image;
}

const gpu::Image& MaterialTextures::image_for(const gpu::Device& device, gpu::CommandRunner& runner,
                                              const scene::Scene& scene, int texture, Kind kind) {
  const auto key = std::make_pair(texture, kind);
  auto it = images_.find(key);
  if (it == images_.end()) {
    const scene::Texture& tex = scene.textures.at(static_cast<std::size_t>(texture));
    if (kind == Kind::MetallicRoughness && tex.width >= 1 && tex.height >= 1 &&
        tex.rgba8.size() == std::size_t(tex.width) * std::size_t(tex.height) * 4) {
      it = images_.emplace(key, upload_mip_chain(device, runner, roughness_mip_chain(tex, kRoughnessMipPower),
                                                 VK_FORMAT_R8G8B8A8_UNORM)).first;
    } else {  // a texture that failed to decode goes the blit path, which reads it as white
      const VkFormat format = kind == Kind::Srgb ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM;
      it = images_.emplace(key, upload_texture(device, runner, tex, format)).first;
    }
  }
  return it->second;
}

namespace {

VkSamplerAddressMode address_mode(scene::Wrap wrap) {
  switch (wrap) {
    case scene::Wrap::ClampToEdge:
      return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    case scene::Wrap::MirroredRepeat:
      return VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT;
    case scene::Wrap::Repeat:
      break;
  }
  return VK_SAMPLER_ADDRESS_MODE_REPEAT;
}

}  // namespace

VkSampler MaterialTextures::sampler_for(const scene::TextureSlot& slot) {
  const SamplerKey key{slot.wrap_s, slot.wrap_t, slot.mag_filter, slot.min_filter, slot.mip_filter};
  auto it = samplers_.find(key);
  if (it != samplers_.end()) return it->second.get();
  auto filter = [](scene::Filter f) {
    return f == scene::Filter::Nearest ? VK_FILTER_NEAREST : VK_FILTER_LINEAR;
  };
  VkSamplerCreateInfo sampler{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  // glTF's magFilter / minFilter, as the path tracer applies them (trace/texture_lookup.h).
  sampler.magFilter = filter(slot.mag_filter);
  sampler.minFilter = filter(slot.min_filter);
  sampler.mipmapMode = slot.mip_filter == scene::MipFilter::Linear ? VK_SAMPLER_MIPMAP_MODE_LINEAR
                                                                   : VK_SAMPLER_MIPMAP_MODE_NEAREST;
  // glTF's wrapS / wrapT, as the path tracer reads them (trace/texture_lookup.h).
  sampler.addressModeU = address_mode(slot.wrap_s);
  sampler.addressModeV = address_mode(slot.wrap_t);
  sampler.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
  // A minFilter without mipmaps reads level 0 only: maxLod 0.25 keeps the magnification /
  // minification choice (lod <= 0) while clamping the level, as the Vulkan specification
  // advises for emulating OpenGL's NEAREST and LINEAR minification.
  sampler.maxLod = slot.mip_filter == scene::MipFilter::None ? 0.25f : VK_LOD_CLAMP_NONE;
  // Off by default on CPU devices, where lavapipe's anisotropic filter can stall a view for
  // tens of seconds (raster/anisotropy.h); never with nearest filters, which ask for texels
  // unblended.
  const bool all_linear = slot.mag_filter == scene::Filter::Linear &&
                          slot.min_filter == scene::Filter::Linear &&
                          slot.mip_filter == scene::MipFilter::Linear;
  if (max_anisotropy_ > 1.0f && all_linear) {
    sampler.anisotropyEnable = VK_TRUE;
    sampler.maxAnisotropy = max_anisotropy_;
  }
  VkSampler s = VK_NULL_HANDLE;
  gpu::check(vkCreateSampler(device_, &sampler, nullptr, &s), "vkCreateSampler");
  return samplers_.emplace(key, gpu::DeviceHandle<VkSampler, vkDestroySampler>{device_, s})
      .first->second.get();
}

MaterialTextures::MaterialTextures(const gpu::Device& device, gpu::CommandRunner& runner,
                                   const scene::Scene& scene, bool textures, int anisotropy)
    : device_(device.handle()),
      max_anisotropy_(resolve_anisotropy(anisotropy, device.info().type,
                                         device.features().sampler_anisotropy,
                                         device.limits().maxSamplerAnisotropy)) {
  scene::Texture white_texel{"white", 1, 1, {255, 255, 255, 255}};
  white_ = upload_texture(device, runner, white_texel, VK_FORMAT_R8G8B8A8_UNORM);

  std::array<VkDescriptorSetLayoutBinding, kSlots + 1> bindings{};
  bindings[0] = {0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr};
  for (std::uint32_t i = 1; i <= kSlots; ++i)
    bindings[i] = {i, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr};
  layout_ = make_descriptor_set_layout(device_, bindings);

  // Scene materials, then glTF's default material for meshes without one.
  std::vector<scene::Material> materials = scene.materials;
  materials.push_back(scene::Material{});
  const auto count = static_cast<std::uint32_t>(materials.size());
  const VkDeviceSize align = std::max<VkDeviceSize>(device.limits().minUniformBufferOffsetAlignment,
                                                    sizeof(MaterialData));
  const VkDeviceSize stride = (sizeof(MaterialData) + align - 1) / align * align;
  stride_ = stride;
  uniforms_ = gpu::Buffer(device, stride * count,
                          VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                          gpu::MemoryUse::upload);

  std::array<VkDescriptorPoolSize, 2> sizes{{{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, count},
                                             {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, count * kSlots}}};
  pool_ = make_descriptor_pool(device_, sizes, count);
  const std::vector<VkDescriptorSetLayout> layouts(count, layout_.get());
  sets_.resize(count);
  allocate_descriptor_sets(device_, pool_.get(), layouts, sets_.data());

  for (std::uint32_t m = 0; m < count; ++m) {
    const scene::Material& mat = materials[m];
    const std::array<std::pair<const scene::TextureSlot*, Kind>, kSlots> slots{{
        {&mat.base_color_texture, Kind::Srgb},
        {&mat.metallic_roughness_texture, Kind::MetallicRoughness},
        {&mat.normal_texture, Kind::Linear},
        {&mat.occlusion_texture, Kind::Linear},
        {&mat.emissive_texture, Kind::Srgb},
    }};
    MaterialData data;
    data.base_color = mat.base_color;
    data.emission = glm::vec4(mat.emission(), mat.unlit ? 1.0f : 0.0f);  // w: KHR_materials_unlit
    data.params = {mat.metallic, mat.roughness, mat.normal_scale, mat.occlusion_strength};
    data.dielectric = glm::vec4(mat.dielectric_f0(), mat.specular);
    std::uint32_t bits = 0;
    std::array<VkDescriptorImageInfo, kSlots> images{};
    for (std::uint32_t i = 0; i < kSlots; ++i) {
      const scene::TextureSlot& slot = *slots[i].first;
      const bool bound = textures && slot && static_cast<std::size_t>(slot.texture) < scene.textures.size();
      const gpu::Image& image = bound ? image_for(device, runner, scene, slot.texture, slots[i].second) : white_;
      if (bound) bits |= 1u << i;
      images[i] = {sampler_for(slot), image.view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    }
    slot_images_.insert(slot_images_.end(), images.begin(), images.end());
    data.alpha = {mat.alpha_cutoff, mat.alpha_mode == scene::AlphaMode::Mask ? 1.0f : 0.0f,
                  static_cast<float>(bits), mat.alpha_mode == scene::AlphaMode::Blend ? 1.0f : 0.0f};
    for (std::uint32_t i = 0; i < kSlots; ++i) {  // KHR_texture_transform and the UV set
      const scene::TextureSlot& slot = *slots[i].first;
      data.uv_rows[2 * i] = glm::vec4(slot.transform.row0(), slot.texcoord == 1 ? 1.0f : 0.0f);
      data.uv_rows[2 * i + 1] = glm::vec4(slot.transform.row1(), 0.0f);
    }
    uniforms_.write(&data, sizeof(data), stride * m);

    VkDescriptorBufferInfo buffer{uniforms_.handle(), stride * m, sizeof(MaterialData)};
    std::array<VkWriteDescriptorSet, kSlots + 1> writes{};
    writes[0] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    writes[0].dstSet = sets_[m];
    writes[0].dstBinding = 0;
    writes[0].descriptorCount = 1;
    writes[0].descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    writes[0].pBufferInfo = &buffer;
    for (std::uint32_t i = 0; i < kSlots; ++i) {
      writes[i + 1] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
      writes[i + 1].dstSet = sets_[m];
      writes[i + 1].dstBinding = i + 1;
      writes[i + 1].descriptorCount = 1;
      writes[i + 1].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
      writes[i + 1].pImageInfo = &images[i];
    }
    vkUpdateDescriptorSets(device_, static_cast<std::uint32_t>(writes.size()), writes.data(), 0, nullptr);
  }
}

VkDescriptorSet MaterialTextures::set(int material) const {
  if (material < 0 || static_cast<std::size_t>(material) + 1 >= sets_.size()) return sets_.back();
  return sets_[static_cast<std::size_t>(material)];
}

}  // namespace ddish::raster
