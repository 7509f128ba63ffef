// The image a window shows for a display, composed on the GPU straight from the renderer's
// buffers: no readback, no quilt held on the CPU. Each batch of views the renderer draws is
// copied (gather) into one persistent buffer of every view's packed RGBA8 display values; after
// the last batch one compute pass (compose) writes the output image, packed the same way (R in
// the low byte, sRGB-encoded, row 0 at the top):
//   atlas       single view, stereo pair (left eye left) or quilt (view 0 bottom-left):
//               shaders/compose_atlas.comp, the tiles copied as they are, so the image equals
//               the PNG app/frame_outputs writes byte for byte;
//   lenticular  the panel image of a Looking Glass calibration, at the panel's resolution:
//               shaders/compose_lenticular.comp, equal bit for bit to display::interleave on
//               the quilt of the same display values (what `--calibration` writes), because
//               everything the calibration decides comes from lenticular.cpp's own functions
//               and the shader repeats interleave's float arithmetic in its order.
// The recording functions only record: the caller submits (raster::RenderRequest::after_batch
// for gather; its own command buffer, before presenting, for compose).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include <glm/glm.hpp>
#include <vulkan/vulkan.h>

#include "display/lenticular.h"
#include "display/quilt_layout.h"
#include "gpu/buffer.h"
#include "gpu/compute_pipeline.h"

namespace ddish::gpu {
class Device;
}

namespace ddish::display {

// The 8-bit sRGB tables the CPU path encodes and decodes with (metrics::srgb8_decode of every
// byte, metrics::srgb8_midpoints): display/ sits above metrics/, so the caller hands them in.
struct Srgb8Tables {
  std::span<const float, 256> decoded;
  std::span<const float, 255> midpoint;
};

class GpuCompositor {
 public:
  // `views` views of layout's tile size. With a mapping the output is the lenticular panel
  // image (screen_width × screen_height), else the atlas (layout.width × layout.height). Throws
  // std::invalid_argument for a layout that does not hold the views, or more than 255 views
  // with a mapping (the subpixel table keeps a byte per view index).
  GpuCompositor(const gpu::Device& device, const QuiltLayout& layout, int views,
                const std::optional<LenticularMapping>& mapping, const Srgb8Tables& tables);

  // Records the copy of views [first_view, first_view + count) from `display` (packed RGBA8,
  // view after view, tile-sized, as raster::BatchViews::display holds them) into the gather
  // buffer. Throws std::invalid_argument for views outside the set or of another size.
  void record_gather(VkCommandBuffer cmd, const gpu::Buffer& display, std::uint32_t first_view,
                     std::uint32_t count, std::uint32_t width, std::uint32_t height) const;

  // A point to mark in every view (the probe-grid overlay): world position and the packed RGBA8
  // colour of its 3 × 3 dot.
  struct OverlayPoint {
    glm::vec3 position;
    std::uint32_t colour;
  };
  // Sets the overlay for the next compose passes: the points and each view's view-projection
  // matrix (Vulkan convention). Empty points: no overlay. The GPU must not be running a compose
  // pass of this compositor meanwhile (the window composes synchronously).
  void set_overlay(std::span<const OverlayPoint> points, std::span<const glm::mat4> view_projections);

  // Sets the status text for the next compose passes (display/status_font.h: the lines, each cut
  // at kStatusColumns, in a dark box at the top-left corner, every length × `scale`): drawn
  // into the composed image for an atlas, into every view before the interleave for a
  // lenticular panel. No lines: no text. Same rule as set_overlay for a running compose pass.
  // Throws std::invalid_argument for a scale below 1.
  void set_status(std::span<const std::string> lines, int scale);

  // Records the compose pass (after the overlay and, for a lenticular panel, the text, if set;
  // for an atlas the text after it), with the barriers from the gathers' transfer writes before it
  // and from its writes to transfer reads of output() after it.
  void record_compose(VkCommandBuffer cmd) const;

  const gpu::Buffer& output() const { return output_; }
  int output_width() const { return output_width_; }
  int output_height() const { return output_height_; }
  bool lenticular() const { return lenticular_.has_value(); }
  const QuiltLayout& layout() const { return layout_; }
  int views() const { return views_; }

 private:
  struct LenticularTables {
    gpu::Buffer subpixel_views;  // one uint per panel pixel
    gpu::Buffer columns;         // one tap per panel column
    gpu::Buffer rows;            // one tap per panel row
    gpu::Buffer srgb;            // 256 decoded values, 255 midpoints
  };

  QuiltLayout layout_;
  int views_ = 0;
  int output_width_ = 0;
  int output_height_ = 0;
  gpu::Buffer gathered_;
  gpu::Buffer output_;
  std::optional<LenticularTables> lenticular_;
  std::optional<gpu::ComputePipeline> pipeline_;
  const gpu::Device* device_ = nullptr;
  std::uint32_t overlay_points_ = 0;
  gpu::Buffer overlay_positions_;  // host-visible, grown as needed
  gpu::Buffer overlay_matrices_;
  std::optional<gpu::ComputePipeline> overlay_;
  std::uint32_t status_lines_ = 0;
  std::uint32_t status_scale_ = 1;
  gpu::Buffer status_cells_;  // host-visible glyph indices, grown as needed
  gpu::Buffer font_;          // the glyph rows, one uint each
  std::optional<gpu::ComputePipeline> status_;

  void record_status(VkCommandBuffer cmd) const;
};

}  // namespace ddish::display
