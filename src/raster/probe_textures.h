// The probe volume on the GPU: its SH coefficients as fp16 3D textures, trilinearly filtered
// by the sampler, and its grid as a uniform buffer, in one descriptor set (set 1 by default,
// PROBE_SET in shaders/include/probe_lighting.glsl, which reads it).
//
// Layout (probe_lighting.glsl explains why): texture_count() RGBA16F 3D textures of
// counts.x × counts.y × counts.z texels, probe (x, y, z) at texel (x, y, z) of each. A probe's
// slots are (w, w c0.r, w c0.g, w c0.b, w c1.r, ...), slot k in component k % 4 of texture
// k / 4, with w = 1 for an active and 0 for an inactive probe (an active probe that has not
// been updated yet counts, with zero radiance): 7 textures (56 bytes a probe) at L2. Values beyond fp16 are saturated to +-65504 and counted, never stored as Inf.
//
// A volume with distance moments (probes/moment_map.h) also gets its moment maps in a storage
// buffer: a header of kMomentHeaderUints uints (uint 0: 1 when some probe of the volume has a
// relocation offset, else 0; the rest 0), then probe i's record at kMomentHeaderUints +
// i * (R^2 + 3) uints, its R x R texels (each two halves, mean d and mean d^2 over the range, low
// half first) then its relocation offset (3 floats, metres), which the shader's visibility
// weights read (the offsets only when the header says some probe has one).
//
// Descriptor set, layout(): binding 0 uniform buffer ProbeGridUniform (std140), binding 1 an
// array of texture_count() combined image samplers (sampler3D probe_sh[]), binding 2 the moment
// storage buffer (a 16-byte placeholder without moments), visible to every stage. A shader compiled with PROBE_SH_ORDER = L reads the first probe_texture_count(L) of
// them, so L must not exceed order().
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <glm/glm.hpp>
#include <vulkan/vulkan.h>

#include "gpu/buffer.h"
#include "gpu/handle.h"
#include "gpu/memory.h"
#include "probes/probe_volume.h"
#include "raster/probe_descriptor_set.h"
#include "raster/probe_import.h"
#include "raster/probe_slots.h"

namespace ddish::gpu {
class CommandRunner;
class Device;
}  // namespace ddish::gpu

namespace ddish::raster {

// std140 mirror of ProbeGridBlock in probe_lighting.glsl.
struct ProbeGridUniform {
  glm::vec4 origin{0.0f};       // xyz: position of probe (0, 0, 0); w: SH order of the textures
  glm::vec4 inv_spacing{0.0f};  // xyz: 1 / cell size, 0 on an axis of zero extent
  glm::vec4 counts{1.0f};       // xyz: probes per axis; w: texture count
  glm::vec4 bounds_min{0.0f};   // xyz: the volume's bounds
  glm::vec4 cell_size{0.0f};    // xyz: distance between neighbouring probes
  // x: moment map resolution R (0: none, trilinear textures only); y: record stride R * R + 3;
  // z: the volume's moment range; w: the distance the visibility test moves the shaded point.
  glm::vec4 visibility{0.0f};
};
static_assert(sizeof(ProbeGridUniform) == 96, "std140 layout of ProbeGridBlock");

// The shaded point is moved this many of the smallest cell sizes off the surface before the
// Chebyshev test (DDGI's 0.75 x 0.3), so a surface does not shadow itself.
inline constexpr float kVisibilityBiasCells = 0.225f;

// Uints before the first probe record in the moment buffer (PROBE_MOMENT_HEADER in
// probe_lighting.glsl).
inline constexpr std::uint32_t kMomentHeaderUints = 4;

struct ProbeUploadStats {
  bool full = false;           // the whole volume was copied (first upload, or most was dirty)
  std::uint32_t probes = 0;    // probes packed and copied
  std::uint32_t regions = 0;   // buffer-to-image copy regions recorded
  std::uint64_t bytes = 0;     // bytes staged by the host (an import: only its probe list)
  bool imported = false;       // converted on the device from GPU data (import()), not packed on the CPU
  SlotClamps clamps;           // values fp16 could not hold, in this upload
};

class ProbeTextures {
 public:
  static constexpr std::uint32_t kGridBinding = 0;
  static constexpr std::uint32_t kShBinding = 1;
  static constexpr std::uint32_t kMomentBinding = 2;
  // A dirty list that falls into more row runs (copy regions per texture) than this fraction
  // of the volume's probes, or holds more than half of them, is uploaded whole. Measured on
  // lavapipe, 16^3 L2 volume (probe_upload_test.cpp, DISABLED_UploadCost; the whole volume
  // takes 0.85-3 ms): a region costs about as much as 30 texels of a whole copy, so 1 %
  // scattered probes upload in 0.3 ms, 5 % scattered in 1.2 ms (whole: 0.9), a 25 % block
  // (64 runs) in 1.6 ms (whole: 3.2), a 50 % block in 4.6 ms (whole: 2.2).
  static constexpr double kFullUploadFraction = 1.0 / 32.0;

  // Textures for the volume's grid at SH order `order` (1..4; 0 takes the volume's order).
  // They hold nothing until the first upload, which copies the whole volume. Throws
  // gpu::GpuError when the device cannot make 3D RGBA16F textures that size, and
  // std::invalid_argument for an order outside 0..4.
  ProbeTextures(const gpu::Device& device, const probes::ProbeVolume& volume, int order = 0);

  // Upload and wait (a CommandRunner submission): every probe, or the dirty ones. The volume
  // must have the grid these textures were made for (std::invalid_argument otherwise); its
  // order may differ (missing bands are zero).
  ProbeUploadStats upload(gpu::CommandRunner& runner, const probes::ProbeVolume& volume);
  ProbeUploadStats upload(gpu::CommandRunner& runner, const probes::ProbeVolume& volume,
                          std::span<const std::uint32_t> dirty_probes);

  // The same, recorded into the caller's command buffer (outside a render pass), with the
  // barriers that order it after earlier shader reads and before later ones. The staging
  // buffer is reused: the previous recorded upload must have finished executing first.
  ProbeUploadStats record_upload(VkCommandBuffer cmd, const probes::ProbeVolume& volume);
  ProbeUploadStats record_upload(VkCommandBuffer cmd, const probes::ProbeVolume& volume,
                                 std::span<const std::uint32_t> dirty_probes);

  // The GPU-resident hand-off (probe_import.h): the same probes as upload() would copy (the
  // same rule for going whole), their coefficients and moments converted on the device from
  // `source`, which holds the volume's averages on this device, their states and offsets taken
  // from `volume`. Waits. The textures and moment buffer then hold exactly what upload() of a
  // volume with those averages would have put there.
  ProbeUploadStats import(gpu::CommandRunner& runner, const probes::ProbeVolume& volume, const GpuProbeData& source,
                          std::span<const std::uint32_t> dirty_probes);

  // Overrides kFullUploadFraction (0 uploads everything every time, >= 1 never goes whole
  // unless it must): for measuring, or for devices where copy regions cost differently.
  void set_full_upload_fraction(double fraction) { full_upload_fraction_ = fraction; }

  // Whether a first upload has been recorded; the set must not be used before.
  bool ready() const { return initialized_; }
  int order() const { return order_; }
  std::uint32_t texture_count() const { return std::uint32_t(textures_.size()); }
  // The volume's moment map resolution (0: none).
  int moment_resolution() const { return moment_res_; }
  const probes::ProbeGrid& grid() const { return grid_; }
  const ProbeGridUniform& grid_uniform() const { return uniform_; }
  // Values saturated or zeroed on their way to fp16 over all uploads so far.
  std::uint64_t clamped_values() const { return clamped_total_; }

  VkDescriptorSetLayout layout() const { return descriptors_.layout(); }
  VkDescriptorSet set() const { return descriptors_.set(); }

 private:
  struct Texture {
    gpu::DeviceMemory memory;  // declared first: destroyed after the image and the view
    gpu::DeviceHandle<VkImage, vkDestroyImage> image;
    gpu::DeviceHandle<VkImageView, vkDestroyImageView> view;
  };

  ProbeUploadStats record(VkCommandBuffer cmd, const probes::ProbeVolume& volume,
                          std::span<const std::uint32_t> dirty, bool everything);
  // The row runs to copy for a dirty list (or the whole volume), filling stats.full and .probes.
  std::vector<ProbeRun> plan_runs(std::span<const std::uint32_t> dirty, bool everything,
                                  ProbeUploadStats& stats) const;
  // Copies the runs' texels and visibility records (staging layout: texture after texture, then
  // the moment header and the records, in run order) from `source` into the textures and the
  // moment buffer, between barriers.
  void record_copies(VkCommandBuffer cmd, VkBuffer source, std::span<const ProbeRun> runs, std::uint32_t n,
                     ProbeUploadStats& stats);
  void check_volume(const probes::ProbeVolume& volume) const;

  const gpu::Device* device_ = nullptr;
  probes::ProbeGrid grid_;
  int order_ = 2;
  ProbeGridUniform uniform_;
  std::vector<Texture> textures_;
  gpu::Buffer staging_;
  gpu::Buffer grid_buffer_;
  gpu::Buffer moments_;  // the moment maps, or a placeholder
  int moment_res_ = 0;
  std::uint32_t record_uints_ = 0;  // uints per probe record (map and offset); 0 without moments
  std::vector<std::uint32_t> moment_scratch_;
  std::unique_ptr<ProbeImporter> importer_;  // made by the first import()
  Sampler sampler_;
  OwnedDescriptorSet descriptors_;
  std::vector<std::uint16_t> texels_;  // packing scratch, kept to avoid reallocation
  bool initialized_ = false;
  double full_upload_fraction_ = kFullUploadFraction;
  std::uint64_t clamped_total_ = 0;
};

}  // namespace ddish::raster
