#include "gpu/buffer.h"

#include <cstring>
#include <string>

#include "gpu/device.h"
#include "gpu/error.h"

namespace ddish::gpu {

Buffer::Buffer(const Device& device, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUse use)
    : size_(size), use_(use) {
  if (size == 0) throw GpuError("a Vulkan buffer cannot be empty (size 0 requested)");
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = size;
  info.usage = usage | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;  // one queue family does everything
  VkBuffer buffer = VK_NULL_HANDLE;
  check(vkCreateBuffer(device.handle(), &info, nullptr, &buffer), "vkCreateBuffer");
  buffer_ = DeviceHandle<VkBuffer, vkDestroyBuffer>(device.handle(), buffer);

  VkMemoryRequirements requirements{};
  vkGetBufferMemoryRequirements(device.handle(), buffer, &requirements);
  const bool addressed = (usage & VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT) != 0;
  memory_ = DeviceMemory(device, requirements, use,
                         addressed ? VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT : 0);
  check(vkBindBufferMemory(device.handle(), buffer, memory_.handle(), 0), "vkBindBufferMemory");
}

VkDeviceAddress Buffer::device_address() const {
  VkBufferDeviceAddressInfo info{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
  info.buffer = buffer_.get();
  return vkGetBufferDeviceAddress(buffer_.device(), &info);
}

void Buffer::check_range(VkDeviceSize bytes, VkDeviceSize offset) const {
  if (!host_visible())
    throw GpuError("buffer of " + std::to_string(size_) +
                   " bytes is not host visible; copy through a staging buffer");
  if (offset > size_ || bytes > size_ - offset)
    throw GpuError("buffer access of " + std::to_string(bytes) + " bytes at offset " +
                   std::to_string(offset) + " leaves a buffer of " + std::to_string(size_) +
                   " bytes");
}

void Buffer::write(const void* data, VkDeviceSize bytes, VkDeviceSize offset) {
  check_range(bytes, offset);
  if (bytes > 0) std::memcpy(static_cast<std::byte*>(mapped()) + offset, data, bytes);
}

void Buffer::read(void* data, VkDeviceSize bytes, VkDeviceSize offset) const {
  check_range(bytes, offset);
  if (bytes > 0) std::memcpy(data, static_cast<const std::byte*>(mapped()) + offset, bytes);
}

}  // namespace ddish::gpu
