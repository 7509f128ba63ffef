#include "gpu/image.h"

#include <string>

#include "gpu/buffer.h"
#include "gpu/device.h"
#include "gpu/error.h"
#include "gpu/format.h"

namespace ddish::gpu {

namespace {

// Asks the device whether it can make the image before trying, so that an unsupported request
// (8x MSAA on lavapipe, 4096 layers) is one readable line instead of a validation error.
void check_supported(const Device& device, const ImageDesc& desc, VkImageUsageFlags usage) {
  const std::string what = std::to_string(desc.width) + "x" + std::to_string(desc.height) +
                           " image of VkFormat " + std::to_string(static_cast<int>(desc.format));
  if (desc.width == 0 || desc.height == 0 || desc.layers == 0 || desc.mip_levels == 0)
    throw GpuError("cannot create an empty " + what + " (" + std::to_string(desc.layers) +
                   " layers, " + std::to_string(desc.mip_levels) + " mips)");
  VkImageFormatProperties props{};
  const VkResult result = vkGetPhysicalDeviceImageFormatProperties(
      device.physical(), desc.format, VK_IMAGE_TYPE_2D, VK_IMAGE_TILING_OPTIMAL, usage, 0, &props);
  if (result == VK_ERROR_FORMAT_NOT_SUPPORTED)
    throw GpuError(device.info().name + " does not support a " + what + " with this usage");
  check(result, "vkGetPhysicalDeviceImageFormatProperties");
  if (desc.width > props.maxExtent.width || desc.height > props.maxExtent.height)
    throw GpuError(what + " exceeds the device's " + std::to_string(props.maxExtent.width) + "x" +
                   std::to_string(props.maxExtent.height));
  if (desc.layers > props.maxArrayLayers)
    throw GpuError(what + ": " + std::to_string(desc.layers) + " layers, the device allows " +
                   std::to_string(props.maxArrayLayers));
  if (desc.mip_levels > props.maxMipLevels)
    throw GpuError(what + ": " + std::to_string(desc.mip_levels) + " mip levels, the device allows " +
                   std::to_string(props.maxMipLevels));
  if ((props.sampleCounts & desc.samples) == 0)
    throw GpuError(what + ": " + std::to_string(desc.samples) +
                   " samples per pixel are not supported (see `ddish devices`)");
}

ImageView create_view(VkDevice device, VkImage image, const ImageDesc& desc,
                      std::uint32_t first_layer, std::uint32_t layer_count) {
  VkImageViewCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  info.image = image;
  // One layer, even of an array, reads as a plain 2D image.
  info.viewType = layer_count > 1 ? VK_IMAGE_VIEW_TYPE_2D_ARRAY : VK_IMAGE_VIEW_TYPE_2D;
  info.format = desc.format;
  // A view may carry only one of depth and stencil when sampled; depth is what ddish samples.
  VkImageAspectFlags aspect = aspect_flags(desc.format);
  if (has_depth(desc.format)) aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
  info.subresourceRange = {aspect, 0, desc.mip_levels, first_layer, layer_count};
  VkImageView view = VK_NULL_HANDLE;
  check(vkCreateImageView(device, &info, nullptr, &view), "vkCreateImageView");
  return ImageView(device, view);
}

}  // namespace

Image::Image(const Device& device, const ImageDesc& desc)
    : desc_(desc), device_(device.handle()) {
  // Transient attachments (MSAA colour and depth that are only resolved) may carry nothing but
  // attachment usages, so they get no transfer bits.
  VkImageUsageFlags usage = desc.usage;
  if ((usage & VK_IMAGE_USAGE_TRANSIENT_ATTACHMENT_BIT) == 0)
    usage |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  check_supported(device, desc, usage);

  VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.imageType = VK_IMAGE_TYPE_2D;
  info.format = desc.format;
  info.extent = {desc.width, desc.height, 1};
  info.mipLevels = desc.mip_levels;
  info.arrayLayers = desc.layers;
  info.samples = desc.samples;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  VkImage image = VK_NULL_HANDLE;
  check(vkCreateImage(device_, &info, nullptr, &image), "vkCreateImage");
  image_ = {device_, image};

  VkMemoryRequirements requirements{};
  vkGetImageMemoryRequirements(device_, image, &requirements);
  memory_ = DeviceMemory(device, requirements, MemoryUse::device_local);
  check(vkBindImageMemory(device_, image, memory_.handle(), 0), "vkBindImageMemory");
  if (viewable()) view_ = create_view(device_, image, desc_, 0, desc_.layers);
}

bool Image::viewable() const {
  constexpr VkImageUsageFlags view_usages =
      VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_STORAGE_BIT |
      VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT |
      VK_IMAGE_USAGE_TRANSIENT_ATTACHMENT_BIT | VK_IMAGE_USAGE_INPUT_ATTACHMENT_BIT;
  return (desc_.usage & view_usages) != 0;
}

VkImageAspectFlags Image::aspect() const { return aspect_flags(desc_.format); }

VkImageSubresourceRange Image::range() const {
  return {aspect(), 0, desc_.mip_levels, 0, desc_.layers};
}

ImageView Image::make_view(std::uint32_t first_layer, std::uint32_t layer_count) const {
  if (!viewable())
    throw GpuError("an image used only for transfers has no views (add a sampled, storage or "
                   "attachment usage)");
  if (layer_count == 0 || first_layer >= desc_.layers || layer_count > desc_.layers - first_layer)
    throw GpuError("image view of layers " + std::to_string(first_layer) + "+" +
                   std::to_string(layer_count) + " of an image with " +
                   std::to_string(desc_.layers));
  return create_view(device_, image_.get(), desc_, first_layer, layer_count);
}

VkDeviceSize Image::layer_bytes() const {
  return VkDeviceSize{desc_.width} * desc_.height * texel_bytes(desc_.format);
}

void image_barrier(VkCommandBuffer cmd, const Image& image, VkImageLayout old_layout,
                   VkImageLayout new_layout, VkPipelineStageFlags src_stage,
                   VkAccessFlags src_access, VkPipelineStageFlags dst_stage,
                   VkAccessFlags dst_access) {
  VkImageMemoryBarrier barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  barrier.srcAccessMask = src_access;
  barrier.dstAccessMask = dst_access;
  barrier.oldLayout = old_layout;
  barrier.newLayout = new_layout;
  barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.image = image.handle();
  barrier.subresourceRange = image.range();
  vkCmdPipelineBarrier(cmd, src_stage, dst_stage, 0, 0, nullptr, 0, nullptr, 1, &barrier);
}

void copy_image_to_buffer(VkCommandBuffer cmd, const Image& image, VkImageLayout layout,
                          std::uint32_t layer, const Buffer& dst, VkDeviceSize offset) {
  const ImageDesc& desc = image.desc();
  if (layer >= desc.layers)
    throw GpuError("copy of layer " + std::to_string(layer) + " of an image with " +
                   std::to_string(desc.layers));
  if (desc.samples != VK_SAMPLE_COUNT_1_BIT)
    throw GpuError("a multisampled image cannot be copied to a buffer; resolve it first");
  if (offset > dst.size() || image.layer_bytes() > dst.size() - offset)
    throw GpuError("image layer of " + std::to_string(image.layer_bytes()) +
                   " bytes does not fit a buffer of " + std::to_string(dst.size()) +
                   " bytes at offset " + std::to_string(offset));
  VkBufferImageCopy region{};
  region.bufferOffset = offset;  // rowLength and imageHeight 0: tightly packed
  region.imageSubresource = {has_depth(desc.format) ? VkImageAspectFlags{VK_IMAGE_ASPECT_DEPTH_BIT}
                                                    : image.aspect(),
                             0, layer, 1};
  region.imageExtent = {desc.width, desc.height, 1};
  vkCmdCopyImageToBuffer(cmd, image.handle(), layout, dst.handle(), 1, &region);
}

}  // namespace ddish::gpu
