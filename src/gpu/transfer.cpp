#include "gpu/transfer.h"

#include <string>

#include "gpu/buffer.h"
#include "gpu/commands.h"
#include "gpu/device.h"
#include "gpu/error.h"

namespace ddish::gpu {

namespace {
// The staged paths hand offsets to vkCmdCopyBuffer, which would not check them; fail here.
void check_range(const Buffer& buffer, VkDeviceSize bytes, VkDeviceSize offset) {
  if (offset > buffer.size() || bytes > buffer.size() - offset)
    throw GpuError("transfer of " + std::to_string(bytes) + " bytes at offset " +
                   std::to_string(offset) + " leaves a buffer of " +
                   std::to_string(buffer.size()) + " bytes");
}
}  // namespace

void copy_buffer(VkCommandBuffer cmd, const Buffer& src, const Buffer& dst, VkDeviceSize bytes,
                 VkDeviceSize src_offset, VkDeviceSize dst_offset) {
  VkBufferCopy region{src_offset, dst_offset, bytes};
  vkCmdCopyBuffer(cmd, src.handle(), dst.handle(), 1, &region);
}

void upload(const Device& device, CommandRunner& runner, Buffer& dst, const void* data,
            VkDeviceSize bytes, VkDeviceSize offset) {
  if (dst.host_visible()) {
    dst.write(data, bytes, offset);
    return;
  }
  check_range(dst, bytes, offset);
  if (bytes == 0) return;
  Buffer staging(device, bytes, 0, MemoryUse::upload);
  staging.write(data, bytes);
  runner.run([&](VkCommandBuffer cmd) {
    copy_buffer(cmd, staging, dst, bytes, 0, offset);
    // The copy's writes become available; the fence wait then orders later submissions after it.
    memory_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                   VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                   VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT);
  });
}

void download(const Device& device, CommandRunner& runner, const Buffer& src, void* data,
              VkDeviceSize bytes, VkDeviceSize offset) {
  if (src.host_visible()) {
    src.read(data, bytes, offset);
    return;
  }
  check_range(src, bytes, offset);
  if (bytes == 0) return;
  Buffer staging(device, bytes, 0, MemoryUse::readback);
  runner.run([&](VkCommandBuffer cmd) {
    copy_buffer(cmd, src, staging, bytes, offset, 0);
    memory_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                   VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
  });
  staging.read(data, bytes);
}

}  // namespace ddish::gpu
