// The environment map (scene/environment_map.h) drawn as the background: a compute pass over
// the resolved HDR pixels (as copied to the readback buffer, before the tonemap) that adds
// (1 - alpha) times the map's radiance in the pixel centre's view direction and sets alpha to 1.
// The forward pass clears to transparent black when the scene has a map, so alpha is the
// coverage of what was drawn (MSAA resolve averages it; BLEND adds alpha + (1 - alpha) dst), and
// edges composite over the map as they do over the clear colour. A separate pass, so that the
// forward shader stays as it is. Lookups are the same bilinear ones as the path tracer's.
#pragma once

#include <cstdint>
#include <span>

#include <vulkan/vulkan.h>

#include "gpu/buffer.h"
#include "gpu/compute_pipeline.h"

namespace ddish::gpu {
class CommandRunner;
class Device;
}  // namespace ddish::gpu

namespace ddish::scene {
struct EnvironmentMap;
struct View;
}  // namespace ddish::scene

namespace ddish::raster {

class EnvironmentBackground {
 public:
  // Uploads the map's texels once.
  EnvironmentBackground(const gpu::Device& device, gpu::CommandRunner& runner,
                        const scene::EnvironmentMap& map);

  // Records the pass over hdr, which holds views.size() images of width x height RGBA16F texels,
  // one after the other. Orders itself after the copy into hdr and before later compute reads.
  void record(VkCommandBuffer cmd, const gpu::Buffer& hdr, std::span<const scene::View> views,
              std::uint32_t width, std::uint32_t height);

 private:
  gpu::Buffer texels_;
  gpu::ComputePipeline pipeline_;
  std::uint32_t map_width_ = 0;
  std::uint32_t map_height_ = 0;
  float rotation_ = 0.0f;
  VkBuffer bound_hdr_ = VK_NULL_HANDLE;
};

}  // namespace ddish::raster
