// The GPU-resident probe hand-off (DESIGN.md, "GPU probe tracing"): when the probe tracer runs on
// the renderer's device, its fp32 running averages are converted into the rasterizer's probe data
// on the device (shaders/probe_import.comp) instead of being read back into the CPU volume and
// uploaded again. The conversion writes a device buffer laid out exactly like ProbeTextures' host
// staging, halves rounded as pack_probe_slots / pack_probe_moments round them, so the copies that
// follow, and the textures and moment buffer they fill, are bit for bit those of an upload of the
// same values. What stays on the CPU: each probe's state and relocation offset (the tracer keeps
// the host volume's up to date every update), which the conversion takes from the volume.
#pragma once

#include <cstdint>
#include <memory>
#include <span>

#include <vulkan/vulkan.h>

#include "gpu/buffer.h"
#include "raster/probe_slots.h"

namespace ddish::gpu {
class ComputePipeline;
class Device;
}  // namespace ddish::gpu
namespace ddish::probes {
class ProbeVolume;
}

namespace ddish::raster {

// A probe volume's averages on the renderer's device, in probes::ProbeVolume's layout: probe
// after probe, volume.coefficient_count() RGB float triples, and volume.moment_texels() float
// pairs (mean d, mean d^2 over the range). Borrowed: the buffers outlive the import that reads
// them, and whatever wrote them was submitted to the device's queue before it.
struct GpuProbeData {
  const gpu::Buffer* coefficients = nullptr;
  const gpu::Buffer* moments = nullptr;  // any buffer when the volume keeps no moments
};

// Where ProbeTextures' staging puts things, for `count` listed probes.
struct StagingLayout {
  std::uint32_t count = 0;          // listed probes
  std::uint32_t texture_count = 0;  // RGBA16F textures: 8 bytes a probe each, texture after texture
  std::uint32_t record_uints = 0;   // per probe visibility record (0: no moments)
  int order = 0;                    // the textures' SH order
  VkDeviceSize texel_bytes() const { return VkDeviceSize{8} * texture_count * count; }
  VkDeviceSize moment_bytes(std::uint32_t header_uints) const {
    return record_uints > 0 ? 4ull * (header_uints + std::uint64_t{record_uints} * count) : 0;
  }
};

class ProbeImporter {
 public:
  explicit ProbeImporter(const gpu::Device& device);
  ~ProbeImporter();
  ProbeImporter(const ProbeImporter&) = delete;
  ProbeImporter& operator=(const ProbeImporter&) = delete;

  // Records the conversion of `probes` (in this order) of `volume` from `source` into staging()
  // with `layout` (layout.count == probes.size() > 0), between barriers that order it after
  // earlier device writes of the source and before transfer reads of staging(). Returns the host
  // bytes written (the probe list: index, state, offset). The previous recorded conversion must
  // have finished executing. Throws std::invalid_argument for source buffers too small for the
  // volume.
  std::uint64_t record(VkCommandBuffer cmd, const probes::ProbeVolume& volume, const GpuProbeData& source,
                       std::span<const std::uint32_t> probes, const StagingLayout& layout);

  const gpu::Buffer& staging() const { return *staging_; }
  // What fp16 could not hold in the last conversion, once it has executed.
  SlotClamps clamps() const;

 private:
  const gpu::Device& device_;
  std::unique_ptr<gpu::ComputePipeline> pipeline_;
  std::unique_ptr<gpu::Buffer> items_;    // the probe list, host written
  std::unique_ptr<gpu::Buffer> staging_;  // device local
  gpu::Buffer clamps_;                    // two counters, read by the host
};

}  // namespace ddish::raster
