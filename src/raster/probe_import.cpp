#include "raster/probe_import.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gpu/commands.h"
#include "gpu/compute_pipeline.h"
#include "gpu/shader.h"
#include "probes/probe_volume.h"
#include "raster/probe_textures.h"
#include "sh/basis.h"

namespace ddish::raster {

namespace {

// probe_import.comp's records.
struct Item {
  std::uint32_t probe = 0;  // bit 31: active
  float offset[3] = {0.0f, 0.0f, 0.0f};
};
static_assert(sizeof(Item) == 16, "std430 layout of probe_import.comp's Item");
constexpr std::uint32_t kActive = 0x80000000u;

struct Params {
  std::uint32_t count, source_coeffs, order_coeffs, texture_count, texels, record_uints, texel_uints, relocated;
};

// Work groups of one dispatch: within every device's minimum maxComputeWorkGroupCount; the
// shader's groups loop over the rest.
constexpr std::uint32_t kMaxGroups = 65535;

constexpr VkBufferUsageFlags kStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;

}  // namespace

ProbeImporter::ProbeImporter(const gpu::Device& device)
    : device_(device),
      pipeline_(std::make_unique<gpu::ComputePipeline>(
          device, gpu::ShaderModule::load(device, "probe_import.comp"),
          gpu::ComputePipelineDesc{.storage_buffers = 5, .push_constant_bytes = sizeof(Params)})),
      clamps_(device, 2 * sizeof(std::uint32_t), kStorage, gpu::MemoryUse::readback) {}

ProbeImporter::~ProbeImporter() = default;

std::uint64_t ProbeImporter::record(VkCommandBuffer cmd, const probes::ProbeVolume& volume,
                                    const GpuProbeData& source, std::span<const std::uint32_t> probes,
                                    const StagingLayout& layout) {
  if (!source.coefficients || !source.moments)
    throw std::invalid_argument("a GPU probe import needs the coefficient and moment buffers");
  const auto coeffs = std::uint32_t(volume.coefficient_count());
  const auto texels = std::uint32_t(volume.moment_texels());
  const VkDeviceSize need_coefficients = VkDeviceSize{volume.probe_count()} * coeffs * sizeof(glm::vec3);
  const VkDeviceSize need_moments = VkDeviceSize{volume.probe_count()} * texels * sizeof(glm::vec2);
  if (source.coefficients->size() < need_coefficients || source.moments->size() < need_moments)
    throw std::invalid_argument("GPU probe buffers of " + std::to_string(source.coefficients->size()) + " and " +
                                std::to_string(source.moments->size()) + " bytes, the volume needs " +
                                std::to_string(need_coefficients) + " and " + std::to_string(need_moments));
  if (volume.probe_count() > kActive)
    throw std::invalid_argument("a GPU probe import takes at most 2^31 probes");
  if (layout.count != probes.size() || probes.empty())
    throw std::invalid_argument("a GPU probe import's layout must count its listed probes");

  std::vector<Item> items(probes.size());
  bool relocated = false;
  for (std::uint32_t p = 0; p < volume.probe_count() && !relocated; ++p)
    relocated = volume.offset(p) != glm::vec3(0.0f);
  for (std::size_t k = 0; k < probes.size(); ++k) {
    items[k].probe = probes[k] | (volume.state(probes[k]).active() ? kActive : 0u);
    const glm::vec3 offset = volume.offset(probes[k]);
    for (int a = 0; a < 3; ++a) items[k].offset[a] = offset[a];
  }
  const VkDeviceSize item_bytes = items.size() * sizeof(Item);
  if (!items_ || items_->size() < item_bytes)
    items_ = std::make_unique<gpu::Buffer>(device_, item_bytes, kStorage, gpu::MemoryUse::upload);
  items_->write(items.data(), item_bytes);
  const VkDeviceSize staging_bytes = layout.texel_bytes() + layout.moment_bytes(kMomentHeaderUints);
  if (!staging_ || staging_->size() < staging_bytes)
    staging_ = std::make_unique<gpu::Buffer>(device_, staging_bytes, kStorage, gpu::MemoryUse::device_local);
  pipeline_->bind_buffers({source.coefficients, source.moments, items_.get(), staging_.get(), &clamps_});

  const Params params{layout.count,
                      coeffs,
                      std::uint32_t(sh::coeff_count(layout.order)),
                      layout.texture_count,
                      layout.record_uints > 0 ? texels : 0u,
                      layout.record_uints,
                      std::uint32_t(layout.texel_bytes() / 4),
                      relocated ? 1u : 0u};
  // The source's writers (the tracer's last submission) and the last import's copies out of
  // staging, before this one reads and writes.
  vkCmdFillBuffer(cmd, clamps_.handle(), 0, VK_WHOLE_SIZE, 0);
  gpu::memory_barrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_WRITE_BIT | VK_ACCESS_TRANSFER_READ_BIT,
                      VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
  pipeline_->bind(cmd);
  pipeline_->push(cmd, params);
  pipeline_->dispatch(cmd, std::min(layout.count, kMaxGroups));
  gpu::memory_barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                      VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_HOST_BIT,
                      VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_HOST_READ_BIT);
  return item_bytes;
}

SlotClamps ProbeImporter::clamps() const {
  const std::vector<std::uint32_t> c = clamps_.read<std::uint32_t>(2);
  return {c[0], c[1]};
}

}  // namespace ddish::raster
