// Moving bytes between the host and buffers of any memory use. A host-visible buffer is copied
// through its mapping; any other goes through a temporary staging buffer and one submission.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include <vulkan/vulkan.h>

namespace ddish::gpu {

class Buffer;
class CommandRunner;
class Device;

// Records a copy of `bytes` bytes from src to dst. The caller places the barriers around it.
void copy_buffer(VkCommandBuffer cmd, const Buffer& src, const Buffer& dst, VkDeviceSize bytes,
                 VkDeviceSize src_offset = 0, VkDeviceSize dst_offset = 0);

// Writes `bytes` bytes at `offset` of dst and waits until they are there. Any GPU work that
// reads dst must be submitted after this returns.
void upload(const Device& device, CommandRunner& runner, Buffer& dst, const void* data,
            VkDeviceSize bytes, VkDeviceSize offset = 0);

// Reads `bytes` bytes at `offset` of src once all submitted work has finished with it. Work that
// wrote src must have finished and made its writes available (a barrier to the transfer or host
// stage at the end of that work).
void download(const Device& device, CommandRunner& runner, const Buffer& src, void* data,
              VkDeviceSize bytes, VkDeviceSize offset = 0);

template <typename T>
void upload(const Device& device, CommandRunner& runner, Buffer& dst, std::span<const T> values) {
  upload(device, runner, dst, values.data(), values.size_bytes());
}

template <typename T>
std::vector<T> download(const Device& device, CommandRunner& runner, const Buffer& src,
                        std::size_t count) {
  std::vector<T> values(count);
  download(device, runner, src, values.data(), count * sizeof(T));
  return values;
}

}  // namespace ddish::gpu
