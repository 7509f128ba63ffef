// Facts about the image formats ddish uses, so that views, barriers and copies pick the right
// aspect and size without each caller listing formats again.
#pragma once

#include <cstdint>

#include <vulkan/vulkan.h>

namespace ddish::gpu {

bool has_depth(VkFormat format);
bool has_stencil(VkFormat format);

// DEPTH (and STENCIL) for depth formats, COLOR otherwise.
VkImageAspectFlags aspect_flags(VkFormat format);

// Bytes per texel of the aspect a copy to a buffer reads: colour formats by their size, depth
// formats by their depth part (D24 copies as 4 bytes, D32 as 4, D16 as 2). Throws GpuError for a
// format the project does not use.
std::uint32_t texel_bytes(VkFormat format);

}  // namespace ddish::gpu
