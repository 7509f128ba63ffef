#include "display/gpu_compositor.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "display/status_font.h"
#include "gpu/commands.h"
#include "gpu/device.h"
#include "gpu/shader.h"
#include "gpu/transfer.h"

namespace ddish::display {

namespace {

constexpr std::uint32_t kGroup = 8;  // local_size_x and _y of both compose shaders

// std430 layout of compose_lenticular.comp's Tap.
struct GpuTap {
  std::int32_t i0;
  std::int32_t i1;
  float f;
  std::int32_t unused;
};

struct AtlasParams {
  std::uint32_t width, height, tile_width, tile_height, columns, rows, view_count;
};

struct OverlayParams {
  std::uint32_t point_count, view_count, width, height;
};

struct StatusParams {
  std::uint32_t width, height, image_count, box_width, box_height, scale, columns, lines;
  std::uint32_t glyph_width, glyph_height, cell_width, cell_height, padding, ink, paper;
};

struct LenticularParams {
  std::uint32_t width, height, tile_width, tile_height;
};

VkDeviceSize pixel_bytes(int width, int height) {
  return VkDeviceSize(width) * VkDeviceSize(height) * sizeof(std::uint32_t);
}

template <typename T>
gpu::Buffer device_buffer(const gpu::Device& device, gpu::CommandRunner& runner,
                          const std::vector<T>& values) {
  gpu::Buffer b(device, values.size() * sizeof(T), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                gpu::MemoryUse::device_local);
  gpu::upload(device, runner, b, std::span<const T>(values));
  return b;
}

}  // namespace

GpuCompositor::GpuCompositor(const gpu::Device& device, const QuiltLayout& layout, int views,
                             const std::optional<LenticularMapping>& mapping,
                             const Srgb8Tables& tables)
    : layout_(layout), views_(views), device_(&device) {
  layout.validate();
  if (views < 1 || views > layout.cells())
    throw std::invalid_argument(std::to_string(views) + " views do not fit a " +
                                std::to_string(layout.columns) + "x" +
                                std::to_string(layout.rows) + " layout");
  if (mapping && views > 255)
    throw std::invalid_argument("the GPU lenticular pass takes at most 255 views, not " +
                                std::to_string(views));
  output_width_ = mapping ? mapping->screen_width : layout.width;
  output_height_ = mapping ? mapping->screen_height : layout.height;
  gathered_ = gpu::Buffer(device, pixel_bytes(layout.tile_width, layout.tile_height) * VkDeviceSize(views),
                          VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUse::device_local);
  output_ = gpu::Buffer(device, pixel_bytes(output_width_, output_height_),
                        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUse::device_local);

  if (!mapping) {
    pipeline_.emplace(device, gpu::ShaderModule::load(device, "compose_atlas.comp"),
                      gpu::ComputePipelineDesc{.storage_buffers = 2,
                                               .push_constant_bytes = sizeof(AtlasParams)});
    pipeline_->bind_buffers({&gathered_, &output_});
    return;
  }

  // Everything the calibration decides, from lenticular.cpp's own functions.
  const LenticularMapping& m = *mapping;
  std::vector<std::uint32_t> subpixel(std::size_t(m.screen_width) * std::size_t(m.screen_height));
  for (int row = 0; row < m.screen_height; ++row)
    for (int x = 0; x < m.screen_width; ++x) {
      std::uint32_t packed = 0;
      for (int c = 0; c < 3; ++c)
        packed |= std::uint32_t(subpixel_view(m, x, row, c, views)) << (8 * c);
      subpixel[std::size_t(row) * std::size_t(m.screen_width) + std::size_t(x)] = packed;
    }
  std::vector<GpuTap> columns, rows;
  for (int x = 0; x < m.screen_width; ++x) {
    const BilinearTap t = tile_tap_x(m, x, layout.tile_width);
    columns.push_back({t.i0, t.i1, t.f, 0});
  }
  for (int row = 0; row < m.screen_height; ++row) {
    const BilinearTap t = tile_tap_y(m, row, layout.tile_height);
    rows.push_back({t.i0, t.i1, t.f, 0});
  }
  std::vector<float> srgb(tables.decoded.begin(), tables.decoded.end());
  srgb.insert(srgb.end(), tables.midpoint.begin(), tables.midpoint.end());

  gpu::CommandRunner runner(device);
  lenticular_ = LenticularTables{device_buffer(device, runner, subpixel),
                                 device_buffer(device, runner, columns),
                                 device_buffer(device, runner, rows),
                                 device_buffer(device, runner, srgb)};
  pipeline_.emplace(device, gpu::ShaderModule::load(device, "compose_lenticular.comp"),
                    gpu::ComputePipelineDesc{.storage_buffers = 6,
                                             .push_constant_bytes = sizeof(LenticularParams)});
  pipeline_->bind_buffers({&gathered_, &output_, &lenticular_->subpixel_views,
                           &lenticular_->columns, &lenticular_->rows, &lenticular_->srgb});
}

void GpuCompositor::record_gather(VkCommandBuffer cmd, const gpu::Buffer& display,
                                  std::uint32_t first_view, std::uint32_t count,
                                  std::uint32_t width, std::uint32_t height) const {
  if (width != std::uint32_t(layout_.tile_width) || height != std::uint32_t(layout_.tile_height) ||
      first_view + count > std::uint32_t(views_) || count == 0)
    throw std::invalid_argument("gather of views " + std::to_string(first_view) + ".." +
                                std::to_string(first_view + count) + " of " +
                                std::to_string(width) + "x" + std::to_string(height) +
                                " into a set of " + std::to_string(views_) + " views of " +
                                std::to_string(layout_.tile_width) + "x" +
                                std::to_string(layout_.tile_height));
  const VkDeviceSize view_bytes = pixel_bytes(int(width), int(height));
  gpu::copy_buffer(cmd, display, gathered_, view_bytes * count, 0, view_bytes * first_view);
}

void GpuCompositor::set_overlay(std::span<const OverlayPoint> points,
                                std::span<const glm::mat4> view_projections) {
  overlay_points_ = 0;
  if (points.empty()) return;
  if (view_projections.size() != std::size_t(views_))
    throw std::invalid_argument("overlay: " + std::to_string(view_projections.size()) +
                                " matrices for " + std::to_string(views_) + " views");
  std::vector<glm::vec4> packed;
  packed.reserve(points.size());
  for (const OverlayPoint& p : points) {
    float colour = 0.0f;
    std::memcpy(&colour, &p.colour, sizeof colour);
    packed.emplace_back(p.position, colour);
  }
  const VkDeviceSize point_bytes = packed.size() * sizeof(glm::vec4);
  const VkDeviceSize matrix_bytes = view_projections.size_bytes();
  const bool rebind = !overlay_ || overlay_positions_.size() < point_bytes ||
                      overlay_matrices_.size() < matrix_bytes;
  if (overlay_positions_.size() < point_bytes)
    overlay_positions_ = gpu::Buffer(*device_, point_bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                     gpu::MemoryUse::upload);
  if (overlay_matrices_.size() < matrix_bytes)
    overlay_matrices_ = gpu::Buffer(*device_, matrix_bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                    gpu::MemoryUse::upload);
  overlay_positions_.write(packed.data(), point_bytes);
  overlay_matrices_.write(view_projections.data(), matrix_bytes);
  if (!overlay_)
    overlay_.emplace(*device_, gpu::ShaderModule::load(*device_, "overlay_points.comp"),
                     gpu::ComputePipelineDesc{.storage_buffers = 3,
                                              .push_constant_bytes = sizeof(OverlayParams)});
  if (rebind) overlay_->bind_buffers({&gathered_, &overlay_positions_, &overlay_matrices_});
  overlay_points_ = std::uint32_t(points.size());
}

void GpuCompositor::set_status(std::span<const std::string> lines, int scale) {
  if (scale < 1) throw std::invalid_argument("status text scale " + std::to_string(scale));
  status_lines_ = 0;
  if (lines.empty()) return;
  const std::vector<std::uint32_t> cells = status_cells(lines);
  const VkDeviceSize bytes = cells.size() * sizeof(std::uint32_t);
  const bool rebind = !status_ || status_cells_.size() < bytes;
  if (status_cells_.size() < bytes)
    status_cells_ = gpu::Buffer(*device_, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUse::upload);
  status_cells_.write(cells.data(), bytes);
  if (!status_) {
    std::vector<std::uint32_t> rows;
    for (const Glyph& g : font_glyphs()) rows.insert(rows.end(), g.begin(), g.end());
    gpu::CommandRunner runner(*device_);
    font_ = device_buffer(*device_, runner, rows);
    status_.emplace(*device_, gpu::ShaderModule::load(*device_, "status_text.comp"),
                    gpu::ComputePipelineDesc{.storage_buffers = 3,
                                             .push_constant_bytes = sizeof(StatusParams)});
  }
  // The text goes where it is read: on the composed atlas, or in every view of a panel.
  if (rebind) status_->bind_buffers({lenticular_ ? &gathered_ : &output_, &status_cells_, &font_});
  status_lines_ = std::uint32_t(lines.size());
  status_scale_ = std::uint32_t(scale);
}

void GpuCompositor::record_status(VkCommandBuffer cmd) const {
  const std::uint32_t scale = status_scale_;
  const auto box_w = std::uint32_t(status_box_width(int(scale)));
  const auto box_h = std::uint32_t(status_box_height(int(status_lines_), int(scale)));
  const bool views = lenticular_.has_value();
  const StatusParams params{
      .width = std::uint32_t(views ? layout_.tile_width : output_width_),
      .height = std::uint32_t(views ? layout_.tile_height : output_height_),
      .image_count = views ? std::uint32_t(views_) : 1u,
      .box_width = box_w,
      .box_height = box_h,
      .scale = scale,
      .columns = std::uint32_t(kStatusColumns),
      .lines = status_lines_,
      .glyph_width = std::uint32_t(kGlyphWidth),
      .glyph_height = std::uint32_t(kGlyphHeight),
      .cell_width = std::uint32_t(kCellWidth),
      .cell_height = std::uint32_t(kCellHeight),
      .padding = std::uint32_t(kTextPadding),
      .ink = kTextInk,
      .paper = kTextPaper};
  status_->bind(cmd);
  status_->push(cmd, params);
  status_->dispatch(cmd, gpu::group_count(std::min(box_w, params.width), kGroup),
                    gpu::group_count(std::min(box_h, params.height), kGroup), params.image_count);
}

void GpuCompositor::record_compose(VkCommandBuffer cmd) const {
  // The gathers may be in earlier submissions: a barrier orders them on the queue all the same.
  gpu::memory_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                      VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
  if (overlay_points_ > 0) {
    overlay_->bind(cmd);
    overlay_->push(cmd, OverlayParams{overlay_points_, std::uint32_t(views_),
                                      std::uint32_t(layout_.tile_width),
                                      std::uint32_t(layout_.tile_height)});
    overlay_->dispatch(cmd, gpu::group_count(overlay_points_ * std::uint32_t(views_), 64));
    gpu::memory_barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                        VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
  }
  if (status_lines_ > 0 && lenticular_) {  // into the views, over the overlay's dots
    record_status(cmd);
    gpu::memory_barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
  }
  // And the last frame's transfer reads of the output before this frame's writes.
  gpu::memory_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT,
                      VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT);
  pipeline_->bind(cmd);
  if (lenticular_) {
    pipeline_->push(cmd, LenticularParams{std::uint32_t(output_width_), std::uint32_t(output_height_),
                                          std::uint32_t(layout_.tile_width),
                                          std::uint32_t(layout_.tile_height)});
  } else {
    pipeline_->push(cmd, AtlasParams{std::uint32_t(layout_.width), std::uint32_t(layout_.height),
                                     std::uint32_t(layout_.tile_width),
                                     std::uint32_t(layout_.tile_height),
                                     std::uint32_t(layout_.columns), std::uint32_t(layout_.rows),
                                     std::uint32_t(views_)});
  }
  pipeline_->dispatch(cmd, gpu::group_count(std::uint32_t(output_width_), kGroup),
                      gpu::group_count(std::uint32_t(output_height_), kGroup));
  if (status_lines_ > 0 && !lenticular_) {  // over the composed atlas
    gpu::memory_barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT);
    record_status(cmd);
  }
  gpu::memory_barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                      VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
}

}  // namespace ddish::display
