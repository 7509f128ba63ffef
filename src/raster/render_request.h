// What a caller asks of one Renderer::render call beyond the views: whether the pixels come back
// to the CPU, and commands of its own to record after each batch of views, on the GPU, before the
// batch's target is reused. The live window and the OpenXR swapchains take the views this way,
// straight from the GPU buffers (a copy or a lenticular interleave), with no CPU round trip.
//
//   raster::RenderRequest request;
//   request.read_back = false;  // the views' pixels stay on the GPU
//   request.after_batch = [&](VkCommandBuffer cmd, const raster::BatchViews& batch) {
//     for (std::uint32_t v = 0; v < batch.count; ++v)
//       copy_into_my_image(cmd, batch.display, batch.display_offset(v), batch.first_view + v);
//   };
//   renderer.render(scene, views, request);
#pragma once

#include <cstdint>
#include <functional>

#include <vulkan/vulkan.h>

namespace ddish::gpu {
class Buffer;
}

namespace ddish::raster {

// One batch's views as the GPU holds them after the tonemap, views [first_view, first_view +
// count) of the frame, each width x height with row 0 at the top:
//   display: packed RGBA8 (R in the low byte), sRGB-encoded display values, 4 bytes a pixel;
//   hdr:     RGBA16F linear radiance (alpha 1), 8 bytes a pixel;
// view after view from offset 0. Both are valid only inside after_batch's command buffer: the
// next batch overwrites them.
struct BatchViews {
  const gpu::Buffer& hdr;
  const gpu::Buffer& display;
  std::uint32_t first_view = 0;
  std::uint32_t count = 0;
  std::uint32_t width = 0;
  std::uint32_t height = 0;

  VkDeviceSize display_offset(std::uint32_t v) const { return VkDeviceSize(width) * height * 4 * v; }
  VkDeviceSize hdr_offset(std::uint32_t v) const { return VkDeviceSize(width) * height * 8 * v; }
};

struct RenderRequest {
  // false: FrameOutput::views keep their sizes but no pixels (nothing is converted on the CPU).
  bool read_back = true;
  // With read_back, false: only the display pixels are converted; ViewImage::linear stays empty
  // (a caller that writes no EXR holds 4 bytes a pixel instead of 10).
  bool linear = true;
  // Recorded after each batch's tonemap, in the batch's command buffer. The writes of the copy
  // into hdr and of the tonemap into display are already made visible to compute, fragment and
  // transfer reads. The submission is synchronous: when render returns, the GPU has run it.
  std::function<void(VkCommandBuffer, const BatchViews&)> after_batch;
};

}  // namespace ddish::raster
