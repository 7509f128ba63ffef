// The tonemap pass: HDR pixels (RGBA16F, as copied from the resolved target) to RGBA8 display
// values on the GPU (shaders/tonemap.comp documents both curves). The linear curve is for error
// figures (no tone curve, like metrics::write_png); the filmic one for looking at.
#pragma once

#include <cstdint>
#include <string>

#include <vulkan/vulkan.h>

#include "gpu/compute_pipeline.h"

namespace ddish::gpu {
class Buffer;
class Device;
}  // namespace ddish::gpu

namespace ddish::raster {

enum class ToneCurve : std::uint32_t { linear = 0, filmic = 1 };

// "linear" or "filmic"; throws std::invalid_argument otherwise.
ToneCurve parse_tone_curve(const std::string& name);
const char* tone_curve_name(ToneCurve curve);

class Tonemapper {
 public:
  explicit Tonemapper(const gpu::Device& device);

  // Records the pass: hdr holds `pixels` RGBA16F texels (8 bytes each), display receives as
  // many packed RGBA8. The caller orders the copy into hdr before and the readback after.
  void record(VkCommandBuffer cmd, const gpu::Buffer& hdr, const gpu::Buffer& display,
              std::uint32_t pixels, ToneCurve curve, float exposure = 1.0f);

 private:
  gpu::ComputePipeline pipeline_;
  // Handles, not addresses: a buffer reassigned in place keeps its address but not its handle.
  VkBuffer bound_hdr_ = VK_NULL_HANDLE;
  VkBuffer bound_display_ = VK_NULL_HANDLE;
};

}  // namespace ddish::raster
