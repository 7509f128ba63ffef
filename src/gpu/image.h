// 2D images (optionally layered and multisampled) in device-local memory, their views, layout
// transitions and readback. Layered images are what multiview renders into: one layer per view.
// Layouts are not tracked: the caller, who knows the frame's order of passes, names both the
// old and the new layout of every transition.
#pragma once

#include <cstdint>

#include <vulkan/vulkan.h>

#include "gpu/handle.h"
#include "gpu/memory.h"

namespace ddish::gpu {

class Buffer;
class Device;

struct ImageDesc {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::uint32_t layers = 1;  // > 1: a 2D array image, e.g. one layer per multiview view
  VkFormat format = VK_FORMAT_R8G8B8A8_UNORM;
  // Transfer source and destination are added unless the image is a transient attachment.
  VkImageUsageFlags usage = 0;
  VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
  std::uint32_t mip_levels = 1;
};

using ImageView = DeviceHandle<VkImageView, vkDestroyImageView>;

class Image {
 public:
  Image() = default;
  // Throws GpuError naming the reason when the device cannot make such an image (format, size,
  // layer count or sample count beyond what it supports for this usage).
  Image(const Device& device, const ImageDesc& desc);

  VkImage handle() const { return image_.get(); }
  const ImageDesc& desc() const { return desc_; }
  VkImageAspectFlags aspect() const;
  // All mips and layers, all aspects.
  VkImageSubresourceRange range() const;
  // A view of every layer and mip: 2D for one layer, 2D array for more (what multiview needs).
  // VK_NULL_HANDLE for an image with transfer usage only, which Vulkan allows no views of.
  VkImageView view() const { return view_.get(); }
  bool viewable() const;
  // A view of `count` layers from `first`, e.g. one view's layer to sample or to copy from.
  ImageView make_view(std::uint32_t first_layer, std::uint32_t layer_count) const;

  // Bytes of one tightly packed layer (mip 0), as copy_image_to_buffer writes it.
  VkDeviceSize layer_bytes() const;

 private:
  ImageDesc desc_;
  VkDevice device_ = VK_NULL_HANDLE;
  // Destroyed in reverse: view, image, then memory.
  DeviceMemory memory_;
  DeviceHandle<VkImage, vkDestroyImage> image_;
  ImageView view_;
};

// A layout transition of every layer and mip of `image`, ordered after `src_access` in
// `src_stage` and before `dst_access` in `dst_stage`. old_layout UNDEFINED discards the contents.
void image_barrier(VkCommandBuffer cmd, const Image& image, VkImageLayout old_layout,
                   VkImageLayout new_layout, VkPipelineStageFlags src_stage,
                   VkAccessFlags src_access, VkPipelineStageFlags dst_stage,
                   VkAccessFlags dst_access);

// Records a copy of mip 0 of `layer` (image in `layout`, TRANSFER_SRC_OPTIMAL or GENERAL) into
// `dst` at `offset`, rows tightly packed: layer_bytes() bytes. For depth/stencil formats the
// depth aspect is copied. Single-sampled images only: resolve multisampled ones first.
void copy_image_to_buffer(VkCommandBuffer cmd, const Image& image, VkImageLayout layout,
                          std::uint32_t layer, const Buffer& dst, VkDeviceSize offset = 0);

}  // namespace ddish::gpu
