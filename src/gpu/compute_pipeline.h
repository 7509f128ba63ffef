// A compute pipeline with the simplest interface that covers most compute work: storage buffers
// at bindings 0..n-1 of descriptor set 0 and one push-constant block. The pipeline owns its one
// descriptor set, so it is bound to one set of buffers at a time.
//
//   ComputePipeline fill(device, ShaderModule::load(device, "fill_pattern.comp"),
//                        {.storage_buffers = 1, .push_constant_bytes = sizeof(Params)});
//   fill.bind_buffers({&out});
//   runner.run([&](VkCommandBuffer cmd) {
//     fill.bind(cmd);
//     fill.push(cmd, params);
//     fill.dispatch(cmd, group_count(n, 64));
//   });
#pragma once

#include <cstdint>
#include <initializer_list>
#include <span>
#include <type_traits>

#include <vulkan/vulkan.h>

#include "gpu/handle.h"

namespace ddish::gpu {

class Buffer;
class Device;
class ShaderModule;

struct ComputePipelineDesc {
  std::uint32_t storage_buffers = 0;      // bindings 0..storage_buffers-1 in set 0
  std::uint32_t push_constant_bytes = 0;  // a multiple of 4, at most the device's limit
  const char* entry_point = "main";
};

// Work groups needed to cover `items` with groups of `group_size` (rounded up).
constexpr std::uint32_t group_count(std::uint32_t items, std::uint32_t group_size) {
  return (items + group_size - 1) / group_size;
}

class ComputePipeline {
 public:
  // The module may be destroyed once the pipeline exists. Throws GpuError for a push-constant
  // block the device cannot take or a failed pipeline build.
  ComputePipeline(const Device& device, const ShaderModule& shader,
                  const ComputePipelineDesc& desc);

  // Points binding i at buffers[i] (whole buffer). Exactly desc.storage_buffers buffers. Must
  // not be called while a submitted command buffer that uses this pipeline is still running.
  void bind_buffers(std::span<const Buffer* const> buffers);
  void bind_buffers(std::initializer_list<const Buffer*> buffers) {
    bind_buffers(std::span<const Buffer* const>(buffers.begin(), buffers.size()));
  }

  // Binds the pipeline and its descriptor set for the dispatches that follow.
  void bind(VkCommandBuffer cmd) const;
  // Sets the push constants (offset 0); bytes <= desc.push_constant_bytes.
  void push(VkCommandBuffer cmd, const void* data, std::uint32_t bytes) const;
  template <typename T>
  void push(VkCommandBuffer cmd, const T& value) const {
    static_assert(std::is_trivially_copyable_v<T>, "push constants are copied as bytes");
    push(cmd, &value, static_cast<std::uint32_t>(sizeof(T)));
  }
  void dispatch(VkCommandBuffer cmd, std::uint32_t x, std::uint32_t y = 1,
                std::uint32_t z = 1) const;

  VkPipeline handle() const { return pipeline_.get(); }
  VkPipelineLayout layout() const { return layout_.get(); }
  VkDescriptorSet descriptor_set() const { return set_; }
  const ComputePipelineDesc& desc() const { return desc_; }

 private:
  ComputePipelineDesc desc_;
  VkDevice device_ = VK_NULL_HANDLE;
  DeviceHandle<VkDescriptorSetLayout, vkDestroyDescriptorSetLayout> set_layout_;
  DeviceHandle<VkPipelineLayout, vkDestroyPipelineLayout> layout_;
  DeviceHandle<VkPipeline, vkDestroyPipeline> pipeline_;
  DeviceHandle<VkDescriptorPool, vkDestroyDescriptorPool> pool_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;  // freed with the pool
};

}  // namespace ddish::gpu
