#include "raster/probe_textures.h"

#include <stdexcept>
#include <string>

#include "gpu/commands.h"
#include "gpu/device.h"
#include "gpu/error.h"

namespace ddish::raster {

namespace {

constexpr VkFormat kFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
constexpr VkDeviceSize kTexelBytes = 8;
// Every stage that may sample the probes (forward fragment shaders, compute harnesses, and
// vertex shaders doing per-vertex lighting).
constexpr VkPipelineStageFlags kReaderStages = VK_PIPELINE_STAGE_VERTEX_SHADER_BIT |
                                               VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT |
                                               VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;

void check_3d_support(const gpu::Device& device, const glm::ivec3& counts) {
  VkImageFormatProperties props{};
  const VkResult result = vkGetPhysicalDeviceImageFormatProperties(
      device.physical(), kFormat, VK_IMAGE_TYPE_3D, VK_IMAGE_TILING_OPTIMAL,
      VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, 0, &props);
  if (result == VK_ERROR_FORMAT_NOT_SUPPORTED)
    throw gpu::GpuError(device.info().name + " has no sampled RGBA16F 3D textures for probes");
  gpu::check(result, "vkGetPhysicalDeviceImageFormatProperties");
  if (std::uint32_t(counts.x) > props.maxExtent.width ||
      std::uint32_t(counts.y) > props.maxExtent.height ||
      std::uint32_t(counts.z) > props.maxExtent.depth)
    throw gpu::GpuError("a probe grid of " + std::to_string(counts.x) + "x" +
                        std::to_string(counts.y) + "x" + std::to_string(counts.z) +
                        " exceeds the device's 3D textures of " +
                        std::to_string(props.maxExtent.width) + "x" +
                        std::to_string(props.maxExtent.height) + "x" +
                        std::to_string(props.maxExtent.depth));
}

void barrier_all(VkCommandBuffer cmd, std::span<const VkImage> images, VkImageLayout from,
                 VkImageLayout to, VkPipelineStageFlags src_stage, VkAccessFlags src_access,
                 VkPipelineStageFlags dst_stage, VkAccessFlags dst_access) {
  std::vector<VkImageMemoryBarrier> barriers(images.size());
  for (std::size_t i = 0; i < images.size(); ++i) {
    VkImageMemoryBarrier& b = barriers[i];
    b = {VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    b.srcAccessMask = src_access;
    b.dstAccessMask = dst_access;
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = images[i];
    b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  }
  vkCmdPipelineBarrier(cmd, src_stage, dst_stage, 0, 0, nullptr, 0, nullptr,
                       std::uint32_t(barriers.size()), barriers.data());
}

}  // namespace

ProbeTextures::ProbeTextures(const gpu::Device& device, const probes::ProbeVolume& volume,
                             int order)
    : device_(&device), grid_(volume.grid()), order_(order == 0 ? volume.sh_order() : order) {
  if (order < 0 || order > sh::kMaxOrder)
    throw std::invalid_argument("probe texture SH order must be 1..4 (0: the volume's), got " +
                                std::to_string(order));
  const glm::ivec3 counts = grid_.counts();
  check_3d_support(device, counts);
  const VkDevice vk = device.handle();
  const auto n_textures = std::uint32_t(probe_texture_count(order_));

  const glm::vec3 spacing = grid_.spacing();
  const glm::vec3 origin = grid_.position(glm::ivec3(0));
  glm::vec3 inv_spacing(0.0f);
  for (int a = 0; a < 3; ++a)
    if (spacing[a] > 0.0f) inv_spacing[a] = 1.0f / spacing[a];
  uniform_.origin = glm::vec4(origin, float(order_));
  uniform_.inv_spacing = glm::vec4(inv_spacing, 0.0f);
  uniform_.counts = glm::vec4(glm::vec3(counts), float(n_textures));
  uniform_.bounds_min = glm::vec4(grid_.bounds().min, 0.0f);
  uniform_.cell_size = glm::vec4(spacing, 0.0f);
  moment_res_ = volume.moment_resolution();
  if (moment_res_ > 0) {
    record_uints_ = std::uint32_t(volume.moment_texels()) + 3;  // the map, then the offset
    uniform_.visibility = glm::vec4(float(moment_res_), float(record_uints_), volume.moment_range(),
                                    kVisibilityBiasCells * volume.grid().smallest_spacing());
  }

  for (std::uint32_t t = 0; t < n_textures; ++t) {
    VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    info.imageType = VK_IMAGE_TYPE_3D;
    info.format = kFormat;
    info.extent = {std::uint32_t(counts.x), std::uint32_t(counts.y), std::uint32_t(counts.z)};
    info.mipLevels = 1;
    info.arrayLayers = 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    Texture tex;
    VkImage image = VK_NULL_HANDLE;
    gpu::check(vkCreateImage(vk, &info, nullptr, &image), "vkCreateImage (probe texture)");
    tex.image = {vk, image};
    VkMemoryRequirements req{};
    vkGetImageMemoryRequirements(vk, image, &req);
    tex.memory = gpu::DeviceMemory(device, req, gpu::MemoryUse::device_local);
    gpu::check(vkBindImageMemory(vk, image, tex.memory.handle(), 0), "vkBindImageMemory");
    VkImageViewCreateInfo view_info{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    view_info.image = image;
    view_info.viewType = VK_IMAGE_VIEW_TYPE_3D;
    view_info.format = kFormat;
    view_info.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkImageView view = VK_NULL_HANDLE;
    gpu::check(vkCreateImageView(vk, &view_info, nullptr, &view), "vkCreateImageView");
    tex.view = {vk, view};
    textures_.push_back(std::move(tex));
  }

  const VkDeviceSize moment_bytes =
      record_uints_ > 0 ? 4ull * (kMomentHeaderUints + record_uints_ * grid_.probe_count()) : 0;
  staging_ = gpu::Buffer(device, kTexelBytes * n_textures * grid_.probe_count() + moment_bytes, 0,
                         gpu::MemoryUse::upload);
  moments_ = gpu::Buffer(device, moment_bytes > 0 ? moment_bytes : 16,
                         VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUse::device_local);
  grid_buffer_ = gpu::Buffer(device, sizeof(ProbeGridUniform), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                             gpu::MemoryUse::upload);
  grid_buffer_.write(&uniform_, sizeof(uniform_));
  sampler_ = make_linear_clamp_sampler(vk);

  const VkDescriptorSetLayoutBinding bindings[] = {
      {kGridBinding, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, VK_SHADER_STAGE_ALL, nullptr},
      {kShBinding, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, n_textures, VK_SHADER_STAGE_ALL,
       nullptr},
      {kMomentBinding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_ALL, nullptr},
  };
  descriptors_ = OwnedDescriptorSet(vk, bindings);
  descriptors_.write_uniform_buffer(kGridBinding, grid_buffer_.descriptor());
  descriptors_.write_storage_buffer(kMomentBinding, moments_.descriptor());
  std::vector<VkDescriptorImageInfo> images;
  for (const Texture& tex : textures_)
    images.push_back({sampler_.get(), tex.view.get(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL});
  descriptors_.write_images(kShBinding, images);
}

void ProbeTextures::check_volume(const probes::ProbeVolume& volume) const {
  if (!(volume.grid() == grid_))
    throw std::invalid_argument(
        "probe volume grid differs from the one its textures were made for");
  if (volume.moment_resolution() != moment_res_)
    throw std::invalid_argument("probe volume has moment maps of resolution " +
                                std::to_string(volume.moment_resolution()) +
                                ", its textures were made for " + std::to_string(moment_res_));
}

ProbeUploadStats ProbeTextures::upload(gpu::CommandRunner& runner,
                                       const probes::ProbeVolume& volume) {
  ProbeUploadStats stats;
  runner.run([&](VkCommandBuffer cmd) { stats = record_upload(cmd, volume); });
  return stats;
}

ProbeUploadStats ProbeTextures::upload(gpu::CommandRunner& runner,
                                       const probes::ProbeVolume& volume,
                                       std::span<const std::uint32_t> dirty_probes) {
  ProbeUploadStats stats;
  runner.run([&](VkCommandBuffer cmd) { stats = record_upload(cmd, volume, dirty_probes); });
  return stats;
}

ProbeUploadStats ProbeTextures::record_upload(VkCommandBuffer cmd,
                                              const probes::ProbeVolume& volume) {
  return record(cmd, volume, {}, true);
}

ProbeUploadStats ProbeTextures::record_upload(VkCommandBuffer cmd,
                                              const probes::ProbeVolume& volume,
                                              std::span<const std::uint32_t> dirty_probes) {
  return record(cmd, volume, dirty_probes, false);
}

std::vector<ProbeRun> ProbeTextures::plan_runs(std::span<const std::uint32_t> dirty, bool everything,
                                               ProbeUploadStats& stats) const {
  const glm::ivec3 counts = grid_.counts();
  const std::uint32_t total = grid_.probe_count();
  std::vector<ProbeRun> runs;
  if (!everything) {
    runs = probe_row_runs(dirty, counts);  // validates the indices even when it goes full
    std::uint64_t n = 0;
    for (const ProbeRun& r : runs) n += r.count;
    everything = !initialized_ || double(runs.size()) > full_upload_fraction_ * double(total) ||
                 (full_upload_fraction_ < 1.0 && 2 * n > total);
  }
  stats.full = everything;
  if (everything) runs = {{0, total}};
  for (const ProbeRun& r : runs) stats.probes += r.count;
  return runs;
}

ProbeUploadStats ProbeTextures::record(VkCommandBuffer cmd, const probes::ProbeVolume& volume,
                                       std::span<const std::uint32_t> dirty, bool everything) {
  check_volume(volume);
  const std::uint32_t total = grid_.probe_count();
  ProbeUploadStats stats;
  const std::vector<ProbeRun> runs = plan_runs(dirty, everything, stats);
  if (stats.probes == 0) return stats;

  // Staging layout: texture t's texels of the listed probes, in list order, at
  // (t * probes + k) texels, so each run is one contiguous range per texture.
  const std::size_t n_tex = textures_.size();
  const std::size_t n = stats.probes;
  texels_.resize(4 * n_tex * n);
  std::vector<std::uint16_t> slots(4 * n_tex);
  std::size_t k = 0;
  for (const ProbeRun& r : runs) {
    for (std::uint32_t p = r.first; p < r.first + r.count; ++p, ++k) {
      pack_probe_slots(volume, p, order_, slots, stats.clamps);
      for (std::size_t t = 0; t < n_tex; ++t)
        std::copy_n(slots.begin() + std::ptrdiff_t(4 * t), 4,
                    texels_.begin() + std::ptrdiff_t(4 * (t * n + k)));
    }
  }
  const VkDeviceSize texel_bytes = kTexelBytes * n_tex * n;
  stats.bytes = texel_bytes;
  staging_.write(texels_.data(), texel_bytes);
  if (record_uints_ > 0) {
    // After the texels: the header (whether any probe of the whole volume is relocated, so that
    // the shader skips reading the offsets when none is), then the listed probes' records in
    // list order.
    moment_scratch_.assign(kMomentHeaderUints + std::size_t(record_uints_) * n, 0u);
    for (std::uint32_t p = 0; p < total && moment_scratch_[0] == 0u; ++p)
      if (volume.offset(p) != glm::vec3(0.0f)) moment_scratch_[0] = 1u;
    k = 0;
    for (const ProbeRun& r : runs)
      for (std::uint32_t p = r.first; p < r.first + r.count; ++p, ++k)
        pack_probe_moments(volume, p,
                           std::span(moment_scratch_)
                               .subspan(kMomentHeaderUints + k * record_uints_, record_uints_),
                           stats.clamps);
    const VkDeviceSize bytes = 4ull * moment_scratch_.size();
    staging_.write(moment_scratch_.data(), bytes, texel_bytes);
    stats.bytes += bytes;
  }
  clamped_total_ += stats.clamps.overflowed + stats.clamps.not_finite;
  record_copies(cmd, staging_.handle(), runs, stats.probes, stats);
  return stats;
}

ProbeUploadStats ProbeTextures::import(gpu::CommandRunner& runner, const probes::ProbeVolume& volume,
                                       const GpuProbeData& source,
                                       std::span<const std::uint32_t> dirty_probes) {
  check_volume(volume);
  ProbeUploadStats stats;
  stats.imported = true;
  const std::vector<ProbeRun> runs = plan_runs(dirty_probes, false, stats);
  if (stats.probes == 0) return stats;
  std::vector<std::uint32_t> listed;
  listed.reserve(stats.probes);
  for (const ProbeRun& r : runs)
    for (std::uint32_t p = r.first; p < r.first + r.count; ++p) listed.push_back(p);
  if (!importer_) importer_ = std::make_unique<ProbeImporter>(*device_);
  const StagingLayout layout{.count = stats.probes,
                             .texture_count = texture_count(),
                             .record_uints = record_uints_,
                             .order = order_};
  runner.run([&](VkCommandBuffer cmd) {
    stats.bytes = importer_->record(cmd, volume, source, listed, layout);
    record_copies(cmd, importer_->staging().handle(), runs, stats.probes, stats);
  });
  stats.clamps = importer_->clamps();
  clamped_total_ += stats.clamps.overflowed + stats.clamps.not_finite;
  return stats;
}

void ProbeTextures::record_copies(VkCommandBuffer cmd, VkBuffer source, std::span<const ProbeRun> runs,
                                  std::uint32_t n, ProbeUploadStats& stats) {
  const glm::ivec3 counts = grid_.counts();
  const std::size_t n_tex = textures_.size();
  const VkDeviceSize texel_bytes = kTexelBytes * n_tex * n;
  if (record_uints_ > 0) {
    VkBufferMemoryBarrier before{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER};
    before.srcAccessMask = initialized_ ? VK_ACCESS_SHADER_READ_BIT : 0;
    before.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    before.srcQueueFamilyIndex = before.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    before.buffer = moments_.handle();
    before.size = VK_WHOLE_SIZE;
    vkCmdPipelineBarrier(cmd, initialized_ ? kReaderStages : VkPipelineStageFlags{VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT},
                         VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 1, &before, 0, nullptr);
    constexpr VkDeviceSize header_bytes = 4ull * kMomentHeaderUints;
    std::vector<VkBufferCopy> copies{{texel_bytes, 0, header_bytes}};
    VkDeviceSize src = texel_bytes + header_bytes;
    for (const ProbeRun& r : runs) {
      const VkDeviceSize size = 4ull * record_uints_ * r.count;
      copies.push_back({src, header_bytes + 4ull * record_uints_ * r.first, size});
      src += size;
    }
    vkCmdCopyBuffer(cmd, source, moments_.handle(), std::uint32_t(copies.size()), copies.data());
    stats.regions += std::uint32_t(copies.size());
    VkBufferMemoryBarrier after_copy = before;
    after_copy.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    after_copy.dstAccessMask = VK_ACCESS_SHADER_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, kReaderStages, 0, 0, nullptr, 1,
                         &after_copy, 0, nullptr);
  }

  std::vector<VkImage> images;
  for (const Texture& tex : textures_) images.push_back(tex.image.get());
  // A first upload discards the undefined contents; later ones keep the probes not copied.
  const VkPipelineStageFlags after =
      initialized_ ? kReaderStages : VkPipelineStageFlags{VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT};
  barrier_all(cmd, images,
              initialized_ ? VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL : VK_IMAGE_LAYOUT_UNDEFINED,
              VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, after, 0, VK_PIPELINE_STAGE_TRANSFER_BIT,
              VK_ACCESS_TRANSFER_WRITE_BIT);
  const bool everything = runs.size() == 1 && runs[0].first == 0 && runs[0].count == grid_.probe_count();
  std::vector<VkBufferImageCopy> regions;
  for (std::size_t t = 0; t < n_tex; ++t) {
    regions.clear();
    if (everything) {
      VkBufferImageCopy region{};
      region.bufferOffset = kTexelBytes * t * n;
      region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
      region.imageExtent = {std::uint32_t(counts.x), std::uint32_t(counts.y),
                            std::uint32_t(counts.z)};
      regions.push_back(region);
    } else {
      std::size_t first_k = 0;
      for (const ProbeRun& r : runs) {
        const glm::ivec3 cell = grid_.cell(r.first);
        VkBufferImageCopy region{};
        region.bufferOffset = kTexelBytes * (t * n + first_k);
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageOffset = {cell.x, cell.y, cell.z};
        region.imageExtent = {r.count, 1, 1};
        regions.push_back(region);
        first_k += r.count;
      }
    }
    vkCmdCopyBufferToImage(cmd, source, images[t], VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                           std::uint32_t(regions.size()), regions.data());
    stats.regions += std::uint32_t(regions.size());
  }
  barrier_all(cmd, images, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
              VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT,
              VK_ACCESS_TRANSFER_WRITE_BIT, kReaderStages, VK_ACCESS_SHADER_READ_BIT);
  initialized_ = true;
}

}  // namespace ddish::raster
