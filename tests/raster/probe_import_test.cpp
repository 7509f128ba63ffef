// The GPU-resident probe hand-off (raster/probe_import.h): the device's conversion of fp32
// averages into the rasterizer's probe data writes the same bits as the CPU's packing, every
// kind of value included (fp16 ties, subnormals, values beyond fp16, NaN and Inf), and
// textures filled by import() shade exactly as textures filled by upload() of the same volume.
#include <gtest/gtest.h>

#include <bit>
#include <limits>
#include <random>
#include <vector>

#include "gpu/buffer.h"
#include "gpu/commands.h"
#include "gpu/transfer.h"
#include "probe_lighting_harness.h"
#include "probe_test_util.h"
#include "raster/probe_import.h"
#include "raster/probe_slots.h"
#include "raster/probe_textures.h"

namespace ddish::raster::test {
namespace {

const scene::Aabb kBounds{glm::vec3(0.0f), glm::vec3(4.0f, 2.0f, 3.0f)};

// A value of every kind the conversion must round like sh::float_to_half: ordinary ones, exact
// ties between two halves (13 low mantissa bits 0x1000), half subnormals and values that
// round to zero, and, now and then, ones fp16 cannot hold.
float any_value(std::mt19937& rng, bool extremes) {
  std::uniform_real_distribution<float> u(-4.0f, 4.0f);
  std::uniform_int_distribution<int> kind(0, extremes ? 9 : 5);
  switch (kind(rng)) {
    case 0:
    case 1:
    case 2:
      return u(rng);
    case 3:  // a tie: the half below is even or odd at random
      return std::bit_cast<float>((std::bit_cast<std::uint32_t>(u(rng)) & ~0x1fffu) | 0x1000u);
    case 4:  // half subnormals (below 2^-14) and the range that rounds to zero (below 2^-25)
      return u(rng) * 1e-5f;
    case 5:
      return u(rng) * 1e-8f;
    case 6:
      return u(rng) * 1e5f;  // mostly beyond 65504
    case 7:
      return std::numeric_limits<float>::quiet_NaN();
    case 8:
      return std::numeric_limits<float>::infinity();
    default:
      return -std::numeric_limits<float>::infinity();
  }
}

// A volume whose coefficients and moments hold values of every kind, with inactive probes and
// relocation offsets.
probes::ProbeVolume wild_volume(std::mt19937& rng, const glm::ivec3& counts, int moment_resolution) {
  probes::ProbeVolume volume(probes::ProbeGrid(kBounds, counts), 2, moment_resolution);
  for (std::uint32_t p = 0; p < volume.probe_count(); ++p) {
    for (glm::vec3& c : volume.coefficients(p))
      for (int k = 0; k < 3; ++k) c[k] = any_value(rng, p % 5 == 2);
    for (glm::vec2& m : volume.moments(p)) m = {any_value(rng, p % 7 == 3), any_value(rng, false)};
  }
  for (std::uint32_t p = 0; p < volume.probe_count(); p += 9) volume.deactivate(p, true);
  volume.set_offset(4, glm::vec3(0.125f, -0.25f, 0.0625f));
  return volume;
}

// The volume's averages as the GPU probe tracer keeps them (ProbeVolume's layout, fp32).
struct DeviceAverages {
  gpu::Buffer coefficients, moments;
  DeviceAverages(const gpu::Device& device, gpu::CommandRunner& runner, const probes::ProbeVolume& v) {
    const auto all = v.all_coefficients();
    coefficients = gpu::Buffer(device, all.size_bytes(), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                               gpu::MemoryUse::device_local);
    gpu::upload(device, runner, coefficients, all.data(), all.size_bytes());
    std::vector<glm::vec2> maps;
    for (std::uint32_t p = 0; p < v.probe_count(); ++p)
      for (const glm::vec2& m : v.moments(p)) maps.push_back(m);
    if (maps.empty()) maps.resize(2);  // a placeholder, as the tracer keeps one
    moments = gpu::Buffer(device, maps.size() * sizeof(glm::vec2), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                          gpu::MemoryUse::device_local);
    gpu::upload(device, runner, moments, maps.data(), maps.size() * sizeof(glm::vec2));
  }
  GpuProbeData data() const { return {&coefficients, &moments}; }
};

class ProbeImportTest : public ProbeGpuTest {};

// The staging the device writes against the one ProbeTextures packs on the CPU (texture after
// texture, then the moment header and records), uint for uint, with the same clamp counts.
TEST_F(ProbeImportTest, ConvertsEveryValueAsTheCpuPackingDoes) {
  std::mt19937 rng(17);
  for (const int resolution : {0, 4}) {
    SCOPED_TRACE("moment resolution " + std::to_string(resolution));
    const probes::ProbeVolume volume = wild_volume(rng, {5, 4, 3}, resolution);
    const DeviceAverages averages(device(), runner(), volume);
    const std::vector<std::uint32_t> listed = {0, 1, 2, 4, 9, 17, 18, 33, 45, 59};
    for (const int order : {2, 1}) {  // the textures' order below the volume's drops bands
      const StagingLayout layout{.count = std::uint32_t(listed.size()),
                                 .texture_count = std::uint32_t(probe_texture_count(order)),
                                 .record_uints = resolution > 0 ? std::uint32_t(volume.moment_texels() + 3) : 0u,
                                 .order = order};
      ProbeImporter importer(device());
      const VkDeviceSize bytes = layout.texel_bytes() + layout.moment_bytes(kMomentHeaderUints);
      gpu::Buffer readback(device(), bytes, 0, gpu::MemoryUse::readback);
      runner().run([&](VkCommandBuffer cmd) {
        EXPECT_EQ(importer.record(cmd, volume, averages.data(), listed, layout), listed.size() * 16u);
        gpu::copy_buffer(cmd, importer.staging(), readback, bytes);
        gpu::memory_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                            VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
      });
      const std::vector<std::uint32_t> got = readback.read<std::uint32_t>(bytes / 4);

      SlotClamps clamps;
      std::vector<std::uint32_t> want(bytes / 4, 0u);
      std::vector<std::uint16_t> slots(4 * layout.texture_count);
      const std::size_t n = listed.size();
      for (std::size_t k = 0; k < n; ++k) {
        pack_probe_slots(volume, listed[k], order, slots, clamps);
        for (std::size_t t = 0; t < layout.texture_count; ++t)
          for (std::size_t h = 0; h < 4; h += 2)
            want[2 * (t * n + k) + h / 2] = slots[4 * t + h] | (std::uint32_t(slots[4 * t + h + 1]) << 16);
      }
      if (resolution > 0) {
        const std::size_t base = layout.texel_bytes() / 4;
        want[base] = 1u;  // probe 4 is relocated
        for (std::size_t k = 0; k < n; ++k)
          pack_probe_moments(volume, listed[k],
                             std::span(want).subspan(base + kMomentHeaderUints + k * layout.record_uints,
                                                     layout.record_uints),
                             clamps);
      }
      int differ = 0;
      for (std::size_t i = 0; i < want.size(); ++i)
        if (got[i] != want[i] && ++differ <= 5)
          ADD_FAILURE() << "order " << order << " uint " << i << ": device " << std::hex << got[i] << ", CPU "
                        << want[i];
      EXPECT_EQ(differ, 0) << "of " << want.size() << " uints";
      EXPECT_GT(clamps.overflowed, 0u);
      EXPECT_GT(clamps.not_finite, 0u);
      EXPECT_EQ(importer.clamps().overflowed, clamps.overflowed);
      EXPECT_EQ(importer.clamps().not_finite, clamps.not_finite);
    }
  }
}

// Two sets of textures start from the same volume; the same probes then change, one set
// uploads them from the CPU, the other imports them from the device: the shader reads the same
// irradiance and visibility-weighted light from both, bit for bit.
TEST_F(ProbeImportTest, ImportedTexturesShadeAsUploadedOnes) {
  std::mt19937 rng(5);
  probes::ProbeVolume volume(probes::ProbeGrid(kBounds, {4, 4, 4}), 2, 4);
  for (std::uint32_t p = 0; p < volume.probe_count(); ++p) {
    volume.set_sh(p, random_sh(rng, 2, 1.0f, 0.3f, false));
    for (glm::vec2& m : volume.moments(p)) m = {0.5f, 0.3f};
  }
  ProbeTextures uploaded(device(), volume), imported(device(), volume);
  uploaded.set_full_upload_fraction(1.0);  // copy just the dirty probes, whatever their runs
  imported.set_full_upload_fraction(1.0);
  uploaded.upload(runner(), volume);
  imported.upload(runner(), volume);

  const std::vector<std::uint32_t> dirty = {5, 6, 7, 21, 40, 63};
  std::uniform_real_distribution<float> u(0.05f, 1.0f);
  for (std::uint32_t p : dirty) {
    volume.set_sh(p, random_sh(rng, 2, 2.0f, 0.5f, false));
    for (glm::vec2& m : volume.moments(p)) {
      const float d = u(rng);
      m = {d, d * d * 1.1f};
    }
  }
  volume.deactivate(40, true);
  volume.set_offset(6, glm::vec3(0.1f, 0.2f, -0.1f));
  const DeviceAverages averages(device(), runner(), volume);
  const ProbeUploadStats up = uploaded.upload(runner(), volume, dirty);
  const ProbeUploadStats in = imported.import(runner(), volume, averages.data(), dirty);
  EXPECT_FALSE(up.imported);
  EXPECT_TRUE(in.imported);
  EXPECT_EQ(in.probes, up.probes);
  EXPECT_EQ(in.regions, up.regions);
  EXPECT_FALSE(in.full);
  // The probe list only (index, state, offset): no coefficient or moment leaves the CPU.
  EXPECT_EQ(in.bytes, dirty.size() * 16u);
  EXPECT_EQ(up.bytes, dirty.size() * (7u * 8u + 4u * 19u) + 16u);

  std::vector<Query> queries;
  std::uniform_real_distribution<float> x(0.0f, 4.0f), y(0.0f, 2.0f), z(0.0f, 3.0f);
  for (int i = 0; i < 256; ++i) {
    const glm::vec3 p(x(rng), y(rng), z(rng)), n = random_direction(rng);
    queries.push_back(i % 2 ? irradiance_query(p, n) : visible_l0_query(p, n));
  }
  const auto a = Harness(device(), uploaded, brdf(), 2).run(runner(), queries);
  const auto b = Harness(device(), imported, brdf(), 2).run(runner(), queries);
  int differ = 0;
  for (std::size_t i = 0; i < queries.size(); ++i)
    if (a[i] != b[i]) ++differ;
  EXPECT_EQ(differ, 0);
  EXPECT_GT(a[1].x, 0.0f);  // the queries see light

  probes::ProbeVolume other(probes::ProbeGrid(kBounds, {4, 4, 5}), 2, 4);
  EXPECT_THROW(imported.import(runner(), other, averages.data(), dirty), std::invalid_argument);
  const gpu::Buffer tiny(device(), 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUse::device_local);
  const GpuProbeData small{&tiny, &averages.moments};
  EXPECT_THROW(imported.import(runner(), volume, small, dirty), std::invalid_argument);
}

}  // namespace
}  // namespace ddish::raster::test
