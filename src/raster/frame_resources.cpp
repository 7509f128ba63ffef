#include "raster/frame_resources.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "gpu/device.h"
#include "gpu/error.h"
#include "raster/probe_descriptor_set.h"
#include "trace/ggx.h"
#include "trace/specular_albedo.h"

namespace ddish::raster {

namespace {

using Table = trace::DielectricSpecularAlbedo;

VkWriteDescriptorSet buffer_write(VkDescriptorSet set, std::uint32_t binding, VkDescriptorType type,
                                  const VkDescriptorBufferInfo* info) {
  VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  w.dstSet = set;
  w.dstBinding = binding;
  w.descriptorCount = 1;
  w.descriptorType = type;
  w.pBufferInfo = info;
  return w;
}

}  // namespace

std::vector<float> FrameResources::albedo_table() {
  // The table's nodes are reproduced by evaluating it exactly at them: roughness node r sits at
  // alpha = kMinAlpha^(1 - y_r), cosine node c at mu = x_c^3 (specular_albedo.cpp's grid).
  // dE/dF0 is another F0 of the dielectric layer (KHR_materials_ior, _specular).
  const Table& table = Table::get();
  constexpr int kCells = Table::kCosNodes - 1;
  auto roughness_at = [](int r) {
    const float y = float(r) / float(Table::kRoughnessNodes - 1);
    return std::sqrt(std::pow(trace::Ggx::kMinAlpha, 1.0f - y));
  };
  auto cosine_at = [](int c) {
    const float x = float(c) / float(Table::kCosNodes - 1);
    return x * x * x;
  };
  std::vector<float> out;
  out.reserve(4 * std::size_t(Table::kRoughnessNodes * kCells + Table::kRoughnessNodes - 1));
  for (int r = 0; r < Table::kRoughnessNodes; ++r)
    for (int c = 0; c < kCells; ++c)
      for (int k = c; k <= c + 1; ++k) {
        out.push_back(table.directional(cosine_at(k), roughness_at(r)));
        out.push_back(table.directional_slope(cosine_at(k), roughness_at(r)));
      }
  for (int r = 0; r + 1 < Table::kRoughnessNodes; ++r)
    for (int k = r; k <= r + 1; ++k) {
      out.push_back(table.average(roughness_at(k)));
      out.push_back(table.average_slope(roughness_at(k)));
    }
  return out;
}

FrameResources::FrameResources(const gpu::Device& device, std::uint32_t max_lights,
                               std::uint32_t max_layers)
    : device_(device.handle()),
      max_lights_(std::max(max_lights, 1u)),
      max_layers_(std::max(max_layers, 1u)) {
  constexpr auto storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  frame_ = gpu::Buffer(device, sizeof(FrameData), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                       gpu::MemoryUse::upload);
  views_ = gpu::Buffer(device, sizeof(ViewData) * kMaxViews, storage, gpu::MemoryUse::upload);
  lights_ = gpu::Buffer(device, sizeof(LightData) * max_lights_, storage, gpu::MemoryUse::upload);
  layers_ = gpu::Buffer(device, sizeof(ShadowLayerData) * max_layers_, storage, gpu::MemoryUse::upload);
  const std::vector<float> table = albedo_table();
  albedo_ = gpu::Buffer(device, table.size() * sizeof(float), storage, gpu::MemoryUse::upload);
  albedo_.write(table.data(), table.size() * sizeof(float));

  constexpr VkShaderStageFlags stages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
  const std::array<VkDescriptorSetLayoutBinding, 6> bindings{{
      {0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, stages, nullptr},
      {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, stages, nullptr},
      {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, stages, nullptr},
      {3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, stages, nullptr},
      {4, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
      {5, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
  }};
  layout_ = make_descriptor_set_layout(device_, bindings);

  const std::array<VkDescriptorPoolSize, 3> sizes{{{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1},
                                                   {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 4},
                                                   {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1}}};
  pool_ = make_descriptor_pool(device_, sizes, 1);
  const VkDescriptorSetLayout layout = layout_.get();
  allocate_descriptor_sets(device_, pool_.get(), {&layout, 1}, &set_);

  const std::array<VkDescriptorBufferInfo, 5> infos{
      {frame_.descriptor(), views_.descriptor(), lights_.descriptor(), layers_.descriptor(),
       albedo_.descriptor()}};
  const std::array<VkWriteDescriptorSet, 5> writes{
      {buffer_write(set_, 0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, &infos[0]),
       buffer_write(set_, 1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &infos[1]),
       buffer_write(set_, 2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &infos[2]),
       buffer_write(set_, 3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &infos[3]),
       buffer_write(set_, 5, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &infos[4])}};
  vkUpdateDescriptorSets(device_, static_cast<std::uint32_t>(writes.size()), writes.data(), 0, nullptr);
}

void FrameResources::update(const FrameData& frame, std::span<const ViewData> views,
                            std::span<const LightData> lights, std::span<const ShadowLayerData> layers) {
  if (views.size() > kMaxViews || lights.size() > max_lights_ || layers.size() > max_layers_)
    throw gpu::GpuError("frame of " + std::to_string(views.size()) + " views, " +
                        std::to_string(lights.size()) + " lights and " +
                        std::to_string(layers.size()) + " shadow layers exceeds the renderer's " +
                        std::to_string(kMaxViews) + ", " + std::to_string(max_lights_) + " and " +
                        std::to_string(max_layers_));
  frame_.write(&frame, sizeof(frame));
  if (!views.empty()) views_.write(views);
  if (!lights.empty()) lights_.write(lights);
  if (!layers.empty()) layers_.write(layers);
}

void FrameResources::bind_shadow_maps(VkImageView view, VkSampler sampler) {
  const VkDescriptorImageInfo image{sampler, view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  w.dstSet = set_;
  w.dstBinding = 4;
  w.descriptorCount = 1;
  w.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  w.pImageInfo = &image;
  vkUpdateDescriptorSets(device_, 1, &w, 0, nullptr);
}

}  // namespace ddish::raster
