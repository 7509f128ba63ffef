// Where the forward pass draws: an HDR colour target (RGBA16F) and depth, one array layer per
// view, multisampled when asked, with a single-sampled resolve image that the readback and the
// tonemapper read. With one sample per pixel the colour target is the resolve image itself; so
// it is too for a multisampled target without multisampled colour (RenderTargetDesc::
// multisampled_color false), whose passes write each pixel's resolved value themselves.
// Multisampled layers are resolved with one vkCmdResolveImage over all layers after the views
// are drawn, not by resolve attachments: with dynamic-rendering resolve attachments, lavapipe
// (Mesa 22.3) left array layer 1 of the resolve image wrong while layer 0 was right, with no
// validation error; RendererTest.SeveralViewsEqualSeparateFrames caught it and guards this.
#pragma once

#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

#include "gpu/image.h"

namespace ddish::gpu {
class Device;
}

namespace ddish::raster {

struct RenderTargetDesc {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::uint32_t layers = 1;  // views
  std::uint32_t samples = 1;
  // > 1: also make views of `block` consecutive layers (the last block may be shorter), what a
  // multiview pass of that many views draws into.
  std::uint32_t block = 0;
  // false: depth keeps its samples but colour has none beyond the resolve image, which the
  // passes draw into directly (the visibility pass's shading writes each pixel's mean over its
  // samples, what the resolve would make of it, and nothing blends over it when the scene has
  // no BLEND material): no multisampled colour is kept (8 bytes a sample) or resolved.
  bool multisampled_color = true;
};

class RenderTarget {
 public:
  static constexpr VkFormat kColorFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
  static constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;

  // Throws GpuError naming the unsupported sample count (with the counts the device has) or
  // the format the device cannot render to.
  RenderTarget(const gpu::Device& device, const RenderTargetDesc& desc);

  const RenderTargetDesc& desc() const { return desc_; }
  VkSampleCountFlagBits samples() const { return static_cast<VkSampleCountFlagBits>(desc_.samples); }
  bool multisampled() const { return desc_.samples > 1; }
  // Whether colour is drawn with the samples and resolved at end_frame (else color_view and
  // color_block_view are the resolve image's).
  bool resolves() const { return multisampled() && desc_.multisampled_color; }

  VkImageView color_view(std::uint32_t layer) const;    // what is drawn into
  VkImageView depth_view(std::uint32_t layer) const { return depth_views_.at(layer).get(); }
  const gpu::Image& resolved() const { return resolved_; }
  // Multiview passes: layers [b * block, b * block + block_layers(b)).
  std::uint32_t block_count() const { return static_cast<std::uint32_t>(depth_blocks_.size()); }
  std::uint32_t block_layers(std::uint32_t b) const;
  VkImageView color_block_view(std::uint32_t b) const;
  VkImageView depth_block_view(std::uint32_t b) const { return depth_blocks_.at(b).get(); }
  // Layered passes: every layer at once.
  VkImageView color_all_view() const { return resolves() ? msaa_color_.view() : resolved_.view(); }
  VkImageView depth_all_view() const { return depth_.view(); }

  // Records the transitions into attachment layouts (contents discarded) before drawing.
  void begin_frame(VkCommandBuffer cmd) const;
  // Records the resolve (when resolves()) and leaves the resolved image ready for copying
  // to a buffer (TRANSFER_SRC_OPTIMAL).
  void end_frame(VkCommandBuffer cmd) const;

 private:
  RenderTargetDesc desc_;
  gpu::Image msaa_color_;  // only when resolves()
  gpu::Image resolved_;
  gpu::Image depth_;
  std::vector<gpu::ImageView> msaa_views_, resolved_views_, depth_views_;
  std::vector<gpu::ImageView> msaa_blocks_, resolved_blocks_, depth_blocks_;
};

}  // namespace ddish::raster
