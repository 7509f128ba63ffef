// The GPU-resident hand-off (DESIGN.md, "GPU probe tracing"): the Vulkan tracer keeps its
// averages on the device (defer_host_copy) and the renderer on the same device converts them
// itself (Renderer::import_probes), against the read-back path (every update copied into the CPU
// volume, uploaded from there) fed the same traced probes: a second tracer with the same seed
// traces the same paths (the GPU tracer is deterministic), so both paths must give the same
// image bit for bit, and the CPU volume read back on demand must equal the read-back path's
// volume, which is the GPU's state. A sphere under the sky in a 3 x 3 x 3 grid whose middle
// probe sits inside it and relocates (the moment header's flag and the offsets travel too, as in
// moment_comparison_test.cpp), an update of every probe then one of some.
#include <algorithm>
#include <cstring>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "../raster/raster_scenes.h"
#include "gpu/buffer.h"
#include "gpu/commands.h"
#include "gpu/transfer.h"
#include "probes/probe_grid.h"
#include "probes/probe_tracer.h"
#include "probes/probe_volume.h"
#include "raster/renderer.h"
#include "scene/scene.h"
#include "scene/view.h"
#include "trace/tracer.h"
#include "trace_vk/vk_probe_tracer.h"
#include "vk_test.h"

namespace ddish::trace_vk::test {
namespace {

class VkHandOff : public VkTracerTest {};

template <typename T>
std::vector<T> read_device(const gpu::Device& device, const gpu::Buffer& buffer) {
  gpu::CommandRunner runner(device);
  gpu::Buffer readback(device, buffer.size(), 0, gpu::MemoryUse::readback);
  runner.run([&](VkCommandBuffer cmd) {
    gpu::memory_barrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_WRITE_BIT,
                        VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
    gpu::copy_buffer(cmd, buffer, readback, buffer.size());
    gpu::memory_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                        VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
  });
  return readback.read<T>(buffer.size() / sizeof(T));
}

bool same_bits(std::span<const glm::vec3> a, std::span<const glm::vec3> b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size_bytes()) == 0;
}
bool same_bits(std::span<const glm::vec2> a, std::span<const glm::vec2> b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size_bytes()) == 0;
}

TEST_F(VkHandOff, RendersAsTheReadBackPathAndReadsBackTheGpuState) {
  scene::Scene s = raster::test::one_mesh_scene(raster::test::uv_sphere(0.3f, 48, 24),
                                                raster::test::make_material({0.7f, 0.7f, 0.7f}, 0.0f, 0.8f));
  s.nodes[0].translation = glm::vec3(1.7f, 1.5f, 1.5f);
  s.pose(0.0);
  s.sidecar.environment = glm::vec3(0.5f, 0.6f, 0.8f);
  const probes::ProbeGrid grid(scene::Aabb{glm::vec3(0.0f), glm::vec3(3.0f)}, {3, 3, 3});
  trace::PathOptions path;
  path.max_bounces = 1;
  probes::UpdateOptions options;
  options.samples = 32;
  options.relocate = true;
  probes::ProbeVolume on_gpu(grid, 2, 4), read_back(grid, 2, 4);
  VkProbeTracer kept(device(), s, path, options), copied(device(), s, path, options);
  kept.defer_host_copy(true);
  raster::RendererOptions ro;
  ro.msaa = 1;
  raster::Renderer handed(device(), s, on_gpu, ro), uploaded(device(), s, read_back, ro);

  std::vector<std::uint32_t> all(grid.probe_count());
  std::iota(all.begin(), all.end(), 0u);
  const std::vector<std::uint32_t> some = {0, 4, 5, 13, 20, 26};
  for (const std::vector<std::uint32_t>* list : {&std::as_const(all), &some}) {
    kept.update(on_gpu, *list);
    copied.update(read_back, *list);
    const raster::ProbeUploadStats in =
        handed.import_probes(on_gpu, {&kept.coefficient_buffer(), &kept.moment_buffer()}, *list);
    const raster::ProbeUploadStats up = uploaded.upload_probes(read_back, *list);
    EXPECT_TRUE(in.imported);
    EXPECT_EQ(in.probes, up.probes);
    EXPECT_EQ(in.bytes, 16u * in.probes);  // the probe list, no traced value
  }
  // The deferred volume is behind (the GPU holds its averages), its states and offsets are not.
  EXPECT_GT(kept.stale_probes(), 0u);
  bool behind = false;
  std::uint32_t relocated = 0;
  for (std::uint32_t p = 0; p < grid.probe_count(); ++p) {
    behind = behind || !same_bits(on_gpu.coefficients(p), read_back.coefficients(p));
    EXPECT_EQ(on_gpu.state(p).flags, read_back.state(p).flags) << "probe " << p;
    EXPECT_EQ(on_gpu.state(p).samples, read_back.state(p).samples) << "probe " << p;
    EXPECT_EQ(on_gpu.offset(p), read_back.offset(p)) << "probe " << p;
    if (on_gpu.offset(p) != glm::vec3(0.0f)) ++relocated;
  }
  EXPECT_TRUE(behind);
  EXPECT_GT(relocated, 0u);

  // The sphere from its relocated probe's side, filling most of the view.
  const scene::View view = scene::look_at_view({0.6f, 1.5f, 1.5f}, {1.7f, 1.5f, 1.5f}, {0.0f, 1.0f, 0.0f},
                                               glm::radians(40.0f), 32, 32);
  const raster::FrameOutput a = handed.render(s, std::span(&view, 1));
  const raster::FrameOutput b = uploaded.render(s, std::span(&view, 1));
  ASSERT_EQ(a.views.size(), 1u);
  ASSERT_EQ(b.views.size(), 1u);
  int differ = 0;
  double sum = 0.0;
  for (std::size_t i = 0; i < a.views[0].linear.size(); ++i) {
    if (a.views[0].linear[i] != b.views[0].linear[i]) ++differ;
    sum += a.views[0].linear[i].x;
  }
  EXPECT_EQ(differ, 0) << "pixels of " << a.views[0].linear.size();
  EXPECT_GT(sum, 0.0);

  // On demand: the deferred volume reads back to the read-back path's, which is the GPU's state.
  kept.read_back(on_gpu);
  EXPECT_EQ(kept.stale_probes(), 0u);
  const auto gpu_coefficients = read_device<glm::vec3>(device(), kept.coefficient_buffer());
  const auto gpu_moments = read_device<glm::vec2>(device(), kept.moment_buffer());
  for (std::uint32_t p = 0; p < grid.probe_count(); ++p) {
    EXPECT_TRUE(same_bits(on_gpu.coefficients(p), read_back.coefficients(p))) << "probe " << p;
    EXPECT_TRUE(same_bits(on_gpu.moments(p), read_back.moments(p))) << "probe " << p;
    const std::size_t n = on_gpu.coefficients(p).size(), t = on_gpu.moments(p).size();
    EXPECT_TRUE(same_bits(on_gpu.coefficients(p), std::span(gpu_coefficients).subspan(p * n, n))) << "probe " << p;
    EXPECT_TRUE(same_bits(on_gpu.moments(p), std::span(gpu_moments).subspan(p * t, t))) << "probe " << p;
  }
  // Deferred values go only into the volume they belong to, and must be read back before the
  // tracer updates another volume (whose copy up would overwrite them on the GPU).
  kept.update(on_gpu, some);
  probes::ProbeVolume other(grid, 2, 4);
  EXPECT_THROW(kept.read_back(other), std::logic_error);
  EXPECT_THROW(kept.update(other, some), std::logic_error);
  kept.read_back(on_gpu);
  kept.update(other, some);
}

}  // namespace
}  // namespace ddish::trace_vk::test
