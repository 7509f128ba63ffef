#include "raster/brdf_tables.h"

#include <chrono>
#include <cmath>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "gpu/commands.h"
#include "gpu/device.h"
#include "gpu/error.h"
#include "sh/ggx_zh.h"
#include "sh/packing.h"
#include "trace/ggx.h"

namespace ddish::raster {

namespace {

std::vector<std::uint16_t> dfg_texels(const DfgTable& dfg) {
  std::vector<std::uint16_t> texels;
  for (const glm::vec2& v : dfg.values) {
    texels.push_back(sh::float_to_half(v.x));
    texels.push_back(sh::float_to_half(v.y));
  }
  return texels;
}

// Copies texels into mip 0 of a fresh image and leaves it ready for sampling.
void record_image_upload(VkCommandBuffer cmd, const gpu::Image& image, const gpu::Buffer& staging,
                         VkDeviceSize offset) {
  gpu::image_barrier(cmd, image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                     VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT,
                     VK_ACCESS_TRANSFER_WRITE_BIT);
  VkBufferImageCopy region{};
  region.bufferOffset = offset;
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {image.desc().width, image.desc().height, 1};
  vkCmdCopyBufferToImage(cmd, staging.handle(), image.handle(),
                         VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
  gpu::image_barrier(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT,
                     VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                     VK_ACCESS_SHADER_READ_BIT);
}

}  // namespace

BrdfTables::BrdfTables(const gpu::Device& device, gpu::CommandRunner& runner) {
  const auto start = std::chrono::steady_clock::now();
  dfg_ = compute_dfg_table();
  dfg_ms_ =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  create(device, runner);
}

BrdfTables::BrdfTables(const gpu::Device& device, gpu::CommandRunner& runner, DfgTable dfg)
    : dfg_(std::move(dfg)) {
  create(device, runner);
}

void BrdfTables::create(const gpu::Device& device, gpu::CommandRunner& runner) {
  const auto dfg_size = std::uint32_t(dfg_.size);
  if (dfg_.size < 2 || dfg_.values.size() != std::size_t(dfg_.size) * std::size_t(dfg_.size))
    throw gpu::GpuError("DFG table has no size x size nodes");
  dfg_image_ = gpu::Image(device, {.width = dfg_size,
                                   .height = dfg_size,
                                   .format = VK_FORMAT_R16G16_SFLOAT,
                                   .usage = VK_IMAGE_USAGE_SAMPLED_BIT});

  const std::vector<std::uint16_t> dfg_data = dfg_texels(dfg_);
  const VkDeviceSize dfg_bytes = dfg_data.size() * sizeof(std::uint16_t);
  gpu::Buffer staging(device, dfg_bytes, 0, gpu::MemoryUse::upload);
  staging.write(dfg_data.data(), dfg_bytes);
  runner.run([&](VkCommandBuffer cmd) { record_image_upload(cmd, dfg_image_, staging, 0); });

  // std140 array of vec4: bands 1..4 of every node (band 0 is 1 by definition).
  const sh::GgxZhTable& zh = sh::ggx_zh_table();
  std::vector<glm::vec4> nodes;
  for (const sh::BandScales& k : zh) nodes.emplace_back(k[1], k[2], k[3], k[4]);
  ggx_zh_buffer_ = gpu::Buffer(device, nodes.size() * sizeof(glm::vec4),
                               VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, gpu::MemoryUse::upload);
  ggx_zh_buffer_.write(nodes.data(), nodes.size() * sizeof(glm::vec4));

  const VkDevice vk = device.handle();
  sampler_ = make_linear_clamp_sampler(vk);
  const VkDescriptorSetLayoutBinding bindings[] = {
      {kDfgBinding, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_ALL, nullptr},
      {kGgxZhBinding, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, VK_SHADER_STAGE_ALL, nullptr},
  };
  descriptors_ = OwnedDescriptorSet(vk, bindings);
  const VkDescriptorImageInfo dfg_info{sampler_.get(), dfg_image_.view(),
                                       VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  descriptors_.write_images(kDfgBinding, {&dfg_info, 1});
  descriptors_.write_uniform_buffer(kGgxZhBinding, ggx_zh_buffer_.descriptor());
}

}  // namespace ddish::raster
