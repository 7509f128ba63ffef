#include "raster/probe_descriptor_set.h"

#include <vector>

#include "gpu/error.h"

namespace ddish::raster {

DescriptorSetLayout make_descriptor_set_layout(VkDevice device,
                                               std::span<const VkDescriptorSetLayoutBinding> bindings) {
  VkDescriptorSetLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  layout_info.bindingCount = static_cast<std::uint32_t>(bindings.size());
  layout_info.pBindings = bindings.data();
  VkDescriptorSetLayout layout = VK_NULL_HANDLE;
  gpu::check(vkCreateDescriptorSetLayout(device, &layout_info, nullptr, &layout),
             "vkCreateDescriptorSetLayout");
  return {device, layout};
}

DescriptorPool make_descriptor_pool(VkDevice device, std::span<const VkDescriptorPoolSize> sizes,
                                    std::uint32_t max_sets) {
  VkDescriptorPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pool_info.maxSets = max_sets;
  pool_info.poolSizeCount = static_cast<std::uint32_t>(sizes.size());
  pool_info.pPoolSizes = sizes.data();
  VkDescriptorPool pool = VK_NULL_HANDLE;
  gpu::check(vkCreateDescriptorPool(device, &pool_info, nullptr, &pool), "vkCreateDescriptorPool");
  return {device, pool};
}

void allocate_descriptor_sets(VkDevice device, VkDescriptorPool pool,
                              std::span<const VkDescriptorSetLayout> layouts, VkDescriptorSet* sets) {
  VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  alloc.descriptorPool = pool;
  alloc.descriptorSetCount = static_cast<std::uint32_t>(layouts.size());
  alloc.pSetLayouts = layouts.data();
  gpu::check(vkAllocateDescriptorSets(device, &alloc, sets), "vkAllocateDescriptorSets");
}

OwnedDescriptorSet::OwnedDescriptorSet(VkDevice device,
                                       std::span<const VkDescriptorSetLayoutBinding> bindings)
    : device_(device), layout_(make_descriptor_set_layout(device, bindings)) {
  std::vector<VkDescriptorPoolSize> sizes;
  for (const auto& b : bindings) sizes.push_back({b.descriptorType, b.descriptorCount});
  pool_ = make_descriptor_pool(device, sizes, 1);
  const VkDescriptorSetLayout layout = layout_.get();
  allocate_descriptor_sets(device, pool_.get(), {&layout, 1}, &set_);
}

namespace {
void write_buffer(VkDevice device, VkDescriptorSet set, std::uint32_t binding, VkDescriptorType type,
                  const VkDescriptorBufferInfo& buffer) {
  VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  write.dstSet = set;
  write.dstBinding = binding;
  write.descriptorCount = 1;
  write.descriptorType = type;
  write.pBufferInfo = &buffer;
  vkUpdateDescriptorSets(device, 1, &write, 0, nullptr);
}
}  // namespace

void OwnedDescriptorSet::write_uniform_buffer(std::uint32_t binding,
                                              const VkDescriptorBufferInfo& buffer) const {
  write_buffer(device_, set_, binding, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, buffer);
}

void OwnedDescriptorSet::write_storage_buffer(std::uint32_t binding,
                                              const VkDescriptorBufferInfo& buffer) const {
  write_buffer(device_, set_, binding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, buffer);
}

void OwnedDescriptorSet::write_images(std::uint32_t binding,
                                      std::span<const VkDescriptorImageInfo> images) const {
  VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  write.dstSet = set_;
  write.dstBinding = binding;
  write.descriptorCount = static_cast<std::uint32_t>(images.size());
  write.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  write.pImageInfo = images.data();
  vkUpdateDescriptorSets(device_, 1, &write, 0, nullptr);
}

Sampler make_linear_clamp_sampler(VkDevice device) {
  VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  info.magFilter = VK_FILTER_LINEAR;
  info.minFilter = VK_FILTER_LINEAR;
  info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  info.addressModeU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  info.addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  info.maxLod = 0.0f;
  VkSampler sampler = VK_NULL_HANDLE;
  gpu::check(vkCreateSampler(device, &info, nullptr, &sampler), "vkCreateSampler");
  return Sampler(device, sampler);
}

}  // namespace ddish::raster
