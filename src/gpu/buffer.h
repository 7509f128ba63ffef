// A VkBuffer with its own memory. Host-visible buffers stay mapped, so reading and writing them is
// a memcpy; device-local ones are filled through transfer.h.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include <vulkan/vulkan.h>

#include "gpu/handle.h"
#include "gpu/memory.h"

namespace ddish::gpu {

class Device;

class Buffer {
 public:
  Buffer() = default;
  // `usage` is what the buffer is for (storage, vertex, index, uniform...); transfer source and
  // destination are always added so that any buffer can be staged and read back. size > 0.
  // With VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT (a device with bufferDeviceAddress, i.e.
  // DeviceFeatures::ray_tracing) the memory is allocated for device addresses.
  Buffer(const Device& device, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUse use);

  VkBuffer handle() const { return buffer_.get(); }
  VkDeviceSize size() const { return size_; }
  MemoryUse use() const { return use_; }
  bool host_visible() const { return memory_.mapped() != nullptr; }
  void* mapped() const { return memory_.mapped(); }
  const DeviceMemory& memory() const { return memory_; }
  VkDescriptorBufferInfo descriptor() const { return {buffer_.get(), 0, size_}; }
  // The buffer's device address; only for buffers made with SHADER_DEVICE_ADDRESS usage.
  VkDeviceAddress device_address() const;

  // Copies bytes in or out through the mapping. Throws GpuError when the buffer is not host
  // visible or the range leaves it. The GPU must not be using the range at the time.
  void write(const void* data, VkDeviceSize bytes, VkDeviceSize offset = 0);
  void read(void* data, VkDeviceSize bytes, VkDeviceSize offset = 0) const;

  template <typename T>
  void write(std::span<const T> values, VkDeviceSize offset = 0) {
    write(values.data(), values.size_bytes(), offset);
  }
  template <typename T>
  std::vector<T> read(std::size_t count, VkDeviceSize offset = 0) const {
    std::vector<T> values(count);
    read(values.data(), count * sizeof(T), offset);
    return values;
  }

 private:
  void check_range(VkDeviceSize bytes, VkDeviceSize offset) const;

  // Declared before the buffer so that the buffer is destroyed first, then its memory.
  DeviceMemory memory_;
  DeviceHandle<VkBuffer, vkDestroyBuffer> buffer_;
  VkDeviceSize size_ = 0;
  MemoryUse use_ = MemoryUse::device_local;
};

}  // namespace ddish::gpu
