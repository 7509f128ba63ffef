#include "gpu/memory.h"

#include <algorithm>
#include <string>

#include "gpu/device.h"
#include "gpu/error.h"
#include "io/host_memory.h"

namespace ddish::gpu {

std::uint32_t find_memory_type(const VkPhysicalDeviceMemoryProperties& properties,
                               std::uint32_t type_bits, VkMemoryPropertyFlags required,
                               VkMemoryPropertyFlags preferred) {
  auto search = [&](VkMemoryPropertyFlags flags) -> int {
    for (std::uint32_t i = 0; i < properties.memoryTypeCount; ++i) {
      const bool allowed = (type_bits & (1u << i)) != 0;
      if (allowed && (properties.memoryTypes[i].propertyFlags & flags) == flags)
        return static_cast<int>(i);
    }
    return -1;
  };
  int index = search(required | preferred);
  if (index < 0) index = search(required);
  if (index < 0)
    throw GpuError("no Vulkan memory type with properties " + std::to_string(required) +
                   " among allowed types " + std::to_string(type_bits));
  return static_cast<std::uint32_t>(index);
}

VkMemoryPropertyFlags required_properties(MemoryUse use) {
  switch (use) {
    case MemoryUse::device_local: return VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
    case MemoryUse::upload:
    case MemoryUse::readback:
      return VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  }
  return 0;
}

VkMemoryPropertyFlags preferred_properties(MemoryUse use) {
  switch (use) {
    case MemoryUse::device_local: return 0;
    // Device-local and host-visible (resizable BAR, unified memory) saves the GPU a trip over
    // the bus for data written once and read often.
    case MemoryUse::upload: return VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
    // Uncached host reads are slow by an order of magnitude.
    case MemoryUse::readback: return VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
  }
  return 0;
}

namespace {
std::atomic<std::int64_t> g_allocations{0};
std::atomic<std::int64_t> g_bytes{0};
}  // namespace

MemoryTally live_device_memory() {
  return {g_allocations.load(std::memory_order_relaxed), g_bytes.load(std::memory_order_relaxed)};
}

std::uint64_t device_memory_available(const Device& device) {
  const VkPhysicalDeviceMemoryProperties& props = device.memory_properties();
  VkDeviceSize heap = 0;
  for (std::uint32_t i = 0; i < props.memoryHeapCount; ++i)
    if (props.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT) heap = std::max(heap, props.memoryHeaps[i].size);
  if (heap == 0)
    for (std::uint32_t i = 0; i < props.memoryHeapCount; ++i) heap = std::max(heap, props.memoryHeaps[i].size);
  const auto held = static_cast<std::uint64_t>(std::max<std::int64_t>(0, live_device_memory().bytes));
  std::uint64_t free = heap > held ? heap - held : 0;
  if (device.info().type == DeviceType::cpu) free = std::min(free, io::host_memory_available());
  return free;
}

void DeviceMemory::release() noexcept {
  if (!memory_.get()) return;
  memory_ = {};
  g_allocations.fetch_sub(1, std::memory_order_relaxed);
  g_bytes.fetch_sub(static_cast<std::int64_t>(size_), std::memory_order_relaxed);
}

DeviceMemory::DeviceMemory(const Device& device, const VkMemoryRequirements& requirements,
                           MemoryUse use, VkMemoryAllocateFlags allocate_flags) {
  const auto& props = device.memory_properties();
  type_index_ = find_memory_type(props, requirements.memoryTypeBits, required_properties(use),
                                 preferred_properties(use));
  properties_ = props.memoryTypes[type_index_].propertyFlags;
  size_ = requirements.size;

  VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  info.allocationSize = requirements.size;
  info.memoryTypeIndex = type_index_;
  VkMemoryAllocateFlagsInfo flags{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
  flags.flags = allocate_flags;
  if (allocate_flags != 0) info.pNext = &flags;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  check(vkAllocateMemory(device.handle(), &info, nullptr, &memory),
        "vkAllocateMemory of " + std::to_string(requirements.size) + " bytes");
  memory_ = DeviceHandle<VkDeviceMemory, vkFreeMemory>(device.handle(), memory);

  // Device-local memory is mapped too when the host can see it coherently (lavapipe, unified
  // memory): then uploads skip the staging copy.
  constexpr VkMemoryPropertyFlags host =
      VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  if ((properties_ & host) == host)
    check(vkMapMemory(device.handle(), memory, 0, VK_WHOLE_SIZE, 0, &mapped_), "vkMapMemory");
  // Counted once nothing can throw: a failed map frees the memory through memory_'s destructor.
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  g_bytes.fetch_add(static_cast<std::int64_t>(size_), std::memory_order_relaxed);
}

DeviceMemory& DeviceMemory::operator=(DeviceMemory&& other) noexcept {
  if (this != &other) {
    release();
    memory_ = std::move(other.memory_);
    size_ = std::exchange(other.size_, 0);
    type_index_ = std::exchange(other.type_index_, 0);
    properties_ = std::exchange(other.properties_, 0);
    mapped_ = std::exchange(other.mapped_, nullptr);
  }
  return *this;
}

}  // namespace ddish::gpu
