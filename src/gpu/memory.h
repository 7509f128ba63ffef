// Device memory: picking a memory type for a use, and an allocation that stays mapped for its
// whole life when the host can see it. One allocation per resource is enough for the handful of
// large buffers and images a frame needs; nothing here sub-allocates.
#pragma once

#include <atomic>
#include <cstdint>
#include <utility>

#include <vulkan/vulkan.h>

#include "gpu/handle.h"

namespace ddish::gpu {

class Device;

enum class MemoryUse {
  device_local,  // GPU-only data (vertex buffers, render targets); may not be host visible
  upload,        // written by the host, read by the GPU: host visible and coherent
  readback,      // written by the GPU, read by the host: host visible, coherent, cached if possible
};

// The first memory type allowed by type_bits that has all `required` properties, preferring one
// that also has all `preferred` ones. Throws GpuError when none qualifies.
std::uint32_t find_memory_type(const VkPhysicalDeviceMemoryProperties& properties,
                               std::uint32_t type_bits, VkMemoryPropertyFlags required,
                               VkMemoryPropertyFlags preferred = 0);

// The required and preferred property flags of a use.
VkMemoryPropertyFlags required_properties(MemoryUse use);
VkMemoryPropertyFlags preferred_properties(MemoryUse use);

// Device memory this process holds through DeviceMemory, over every device: the count and bytes
// of live vkAllocateMemory allocations. A long run's figures must stay flat (scripts/soak.sh).
struct MemoryTally {
  std::int64_t allocations = 0;
  std::int64_t bytes = 0;
};
MemoryTally live_device_memory();

// What a new allocation may still take, in bytes: the largest device-local heap less what this
// process holds there; on a CPU device (lavapipe, whose heap is the whole of system memory) also
// at most the system's available memory. Callers check a large target against it first, so that
// an impossible size is one clear error, not the kernel's out-of-memory killer.
std::uint64_t device_memory_available(const Device& device);

class DeviceMemory {
 public:
  DeviceMemory() = default;
  // Allocates memory meeting `requirements` for `use`, mapped when host visible. Coherence is
  // required of host-visible types, so writes through mapped() need no flush.
  // allocate_flags: VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT for buffers read by address
  // (acceleration-structure inputs and storage).
  DeviceMemory(const Device& device, const VkMemoryRequirements& requirements, MemoryUse use,
               VkMemoryAllocateFlags allocate_flags = 0);
  DeviceMemory(DeviceMemory&& other) noexcept { *this = std::move(other); }
  DeviceMemory& operator=(DeviceMemory&& other) noexcept;
  ~DeviceMemory() { release(); }

  VkDeviceMemory handle() const { return memory_.get(); }
  VkDeviceSize size() const { return size_; }
  std::uint32_t type_index() const { return type_index_; }
  VkMemoryPropertyFlags properties() const { return properties_; }
  // The host address of the whole allocation, or nullptr when it is not host visible and
  // coherent.
  void* mapped() const { return mapped_; }

 private:
  void release() noexcept;  // frees the allocation and takes it off the tally

  // Freeing mapped memory unmaps it implicitly, so no separate unmap step is needed.
  DeviceHandle<VkDeviceMemory, vkFreeMemory> memory_;
  VkDeviceSize size_ = 0;
  std::uint32_t type_index_ = 0;
  VkMemoryPropertyFlags properties_ = 0;
  void* mapped_ = nullptr;
};

}  // namespace ddish::gpu
