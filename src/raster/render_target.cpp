#include "raster/render_target.h"

#include <algorithm>
#include <string>

#include "gpu/device.h"
#include "gpu/device_info.h"
#include "gpu/error.h"

namespace ddish::raster {

namespace {

std::string counts_text(VkSampleCountFlags flags) {
  std::string text;
  for (std::uint32_t c : gpu::sample_counts(flags)) text += (text.empty() ? "" : ", ") + std::to_string(c);
  return text.empty() ? "none" : text;
}

}  // namespace

RenderTarget::RenderTarget(const gpu::Device& device, const RenderTargetDesc& desc) : desc_(desc) {
  const VkSampleCountFlags counts = device.info().msaa_sample_counts();
  if (desc.samples == 0 || (desc.samples & (desc.samples - 1)) != 0 || (counts & desc.samples) == 0)
    throw gpu::GpuError(device.info().name + " cannot render with " + std::to_string(desc.samples) +
                        " samples per pixel (MSAA counts it supports for colour and depth: " +
                        counts_text(counts) + ")");
  const auto samples = static_cast<VkSampleCountFlagBits>(desc.samples);
  if (resolves())
    msaa_color_ = gpu::Image(device, {.width = desc.width, .height = desc.height, .layers = desc.layers,
                                      .format = kColorFormat,
                                      .usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, .samples = samples});
  resolved_ = gpu::Image(device, {.width = desc.width, .height = desc.height, .layers = desc.layers,
                                  .format = kColorFormat, .usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT});
  depth_ = gpu::Image(device, {.width = desc.width, .height = desc.height, .layers = desc.layers,
                               .format = kDepthFormat,
                               .usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, .samples = samples});
  for (std::uint32_t i = 0; i < desc.layers; ++i) {
    if (resolves()) msaa_views_.push_back(msaa_color_.make_view(i, 1));
    resolved_views_.push_back(resolved_.make_view(i, 1));
    depth_views_.push_back(depth_.make_view(i, 1));
  }
  if (desc.block > 1)
    for (std::uint32_t first = 0; first < desc.layers; first += desc.block) {
      const std::uint32_t count = std::min(desc.block, desc.layers - first);
      if (resolves()) msaa_blocks_.push_back(msaa_color_.make_view(first, count));
      resolved_blocks_.push_back(resolved_.make_view(first, count));
      depth_blocks_.push_back(depth_.make_view(first, count));
    }
}

std::uint32_t RenderTarget::block_layers(std::uint32_t b) const {
  return std::min(desc_.block, desc_.layers - b * desc_.block);
}

VkImageView RenderTarget::color_block_view(std::uint32_t b) const {
  return resolves() ? msaa_blocks_.at(b).get() : resolved_blocks_.at(b).get();
}

VkImageView RenderTarget::color_view(std::uint32_t layer) const {
  return resolves() ? msaa_views_.at(layer).get() : resolved_views_.at(layer).get();
}

void RenderTarget::begin_frame(VkCommandBuffer cmd) const {
  // The previous frame's copy (transfer) read the resolved image; the one before drew it.
  const VkPipelineStageFlags color_stages =
      VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  const VkAccessFlags color_access =
      VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  if (resolves())
    gpu::image_barrier(cmd, msaa_color_, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                       color_stages, 0, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, color_access);
  gpu::image_barrier(cmd, resolved_, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                     color_stages, 0, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, color_access);
  const VkPipelineStageFlags depth_stages =
      VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  gpu::image_barrier(cmd, depth_, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                     depth_stages, 0, depth_stages,
                     VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
}

void RenderTarget::end_frame(VkCommandBuffer cmd) const {
  if (!resolves()) {
    gpu::image_barrier(cmd, resolved_, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                       VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                       VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_ACCESS_TRANSFER_READ_BIT);
    return;
  }
  gpu::image_barrier(cmd, msaa_color_, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                     VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                     VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                     VK_ACCESS_TRANSFER_READ_BIT);
  gpu::image_barrier(cmd, resolved_, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                     VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                     0, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
  VkImageResolve region{};
  region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, desc_.layers};
  region.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, desc_.layers};
  region.extent = {desc_.width, desc_.height, 1};
  vkCmdResolveImage(cmd, msaa_color_.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, resolved_.handle(),
                    VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
  gpu::image_barrier(cmd, resolved_, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                     VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT,
                     VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                     VK_ACCESS_TRANSFER_READ_BIT);
}

}  // namespace ddish::raster
