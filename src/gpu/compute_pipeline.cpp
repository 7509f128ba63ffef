#include "gpu/compute_pipeline.h"

#include <string>
#include <vector>

#include "gpu/buffer.h"
#include "gpu/device.h"
#include "gpu/error.h"
#include "gpu/shader.h"

namespace ddish::gpu {

ComputePipeline::ComputePipeline(const Device& device, const ShaderModule& shader,
                                 const ComputePipelineDesc& desc)
    : desc_(desc), device_(device.handle()) {
  if (desc.push_constant_bytes % 4 != 0 ||
      desc.push_constant_bytes > device.limits().maxPushConstantsSize)
    throw GpuError("compute push constants of " + std::to_string(desc.push_constant_bytes) +
                   " bytes: must be a multiple of 4 and at most " +
                   std::to_string(device.limits().maxPushConstantsSize));

  std::vector<VkDescriptorSetLayoutBinding> bindings(desc.storage_buffers);
  for (std::uint32_t i = 0; i < desc.storage_buffers; ++i) {
    bindings[i].binding = i;
    bindings[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    bindings[i].descriptorCount = 1;
    bindings[i].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
  }
  VkDescriptorSetLayoutCreateInfo set_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  set_info.bindingCount = desc.storage_buffers;
  set_info.pBindings = bindings.data();
  VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
  check(vkCreateDescriptorSetLayout(device_, &set_info, nullptr, &set_layout),
        "vkCreateDescriptorSetLayout");
  set_layout_ = {device_, set_layout};

  VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, desc.push_constant_bytes};
  VkPipelineLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layout_info.setLayoutCount = 1;
  layout_info.pSetLayouts = &set_layout;
  layout_info.pushConstantRangeCount = desc.push_constant_bytes > 0 ? 1 : 0;
  layout_info.pPushConstantRanges = &range;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  check(vkCreatePipelineLayout(device_, &layout_info, nullptr, &layout), "vkCreatePipelineLayout");
  layout_ = {device_, layout};

  VkComputePipelineCreateInfo pipeline_info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  pipeline_info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  pipeline_info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  pipeline_info.stage.module = shader.handle();
  pipeline_info.stage.pName = desc.entry_point;
  pipeline_info.layout = layout;
  VkPipeline pipeline = VK_NULL_HANDLE;
  check(vkCreateComputePipelines(device_, VK_NULL_HANDLE, 1, &pipeline_info, nullptr, &pipeline),
        "vkCreateComputePipelines");
  pipeline_ = {device_, pipeline};

  if (desc.storage_buffers == 0) return;  // a set without bindings needs no pool
  VkDescriptorPoolSize pool_size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, desc.storage_buffers};
  VkDescriptorPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pool_info.maxSets = 1;
  pool_info.poolSizeCount = 1;
  pool_info.pPoolSizes = &pool_size;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  check(vkCreateDescriptorPool(device_, &pool_info, nullptr, &pool), "vkCreateDescriptorPool");
  pool_ = {device_, pool};

  VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  alloc.descriptorPool = pool;
  alloc.descriptorSetCount = 1;
  alloc.pSetLayouts = &set_layout;
  check(vkAllocateDescriptorSets(device_, &alloc, &set_), "vkAllocateDescriptorSets");
}

void ComputePipeline::bind_buffers(std::span<const Buffer* const> buffers) {
  if (buffers.size() != desc_.storage_buffers)
    throw GpuError("compute pipeline takes " + std::to_string(desc_.storage_buffers) +
                   " storage buffers, " + std::to_string(buffers.size()) + " given");
  std::vector<VkDescriptorBufferInfo> infos(buffers.size());
  std::vector<VkWriteDescriptorSet> writes(buffers.size());
  for (std::size_t i = 0; i < buffers.size(); ++i) {
    if (buffers[i] == nullptr || buffers[i]->handle() == VK_NULL_HANDLE)
      throw GpuError("storage buffer " + std::to_string(i) + " of a compute pipeline is empty");
    infos[i] = buffers[i]->descriptor();
    writes[i] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    writes[i].dstSet = set_;
    writes[i].dstBinding = static_cast<std::uint32_t>(i);
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writes[i].pBufferInfo = &infos[i];
  }
  vkUpdateDescriptorSets(device_, static_cast<std::uint32_t>(writes.size()), writes.data(), 0,
                         nullptr);
}

void ComputePipeline::bind(VkCommandBuffer cmd) const {
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_.get());
  if (set_ != VK_NULL_HANDLE)
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.get(), 0, 1, &set_, 0,
                            nullptr);
}

void ComputePipeline::push(VkCommandBuffer cmd, const void* data, std::uint32_t bytes) const {
  if (bytes > desc_.push_constant_bytes)
    throw GpuError("push of " + std::to_string(bytes) + " bytes into a block of " +
                   std::to_string(desc_.push_constant_bytes));
  if (bytes > 0)
    vkCmdPushConstants(cmd, layout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, bytes, data);
}

void ComputePipeline::dispatch(VkCommandBuffer cmd, std::uint32_t x, std::uint32_t y,
                               std::uint32_t z) const {
  vkCmdDispatch(cmd, x, y, z);
}

}  // namespace ddish::gpu
