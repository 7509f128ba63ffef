// The GPU probe tracer on scenes with exact answers: a uniform sky and an environment map with
// nothing in the way (no randomness at all: the same lattice and rotations as the CPU tracer,
// so the same coefficients to rounding) and a probe inside a closed box (classified inside geometry, as the CPU tracer does).
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "probes/probe_tracer.h"
#include "probes/tracer_source.h"
#include "scene/scene.h"
#include "trace/tracer.h"
#include "trace_vk/vk_probe_tracer.h"
#include "test_environment.h"
#include "vk_test.h"

namespace ddish::trace_vk::test {
namespace {

using probes::ProbeGrid;
using probes::ProbeVolume;
using probes::UpdateOptions;
using scene::Aabb;

// A closed axis-aligned box of single-sided quads facing outward.
void add_box(scene::Scene& s, const glm::vec3& lo, const glm::vec3& hi) {
  scene::Mesh m;
  m.name = "box";
  for (int i = 0; i < 8; ++i) m.positions.push_back({i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z});
  // Counter-clockwise seen from outside.
  m.indices = {0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6, 0, 1, 5, 0, 5, 4,
               2, 6, 7, 2, 7, 3, 0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5};
  m.material = 0;
  scene::Material grey;
  grey.base_color = glm::vec4(0.5f, 0.5f, 0.5f, 1.0f);
  grey.metallic = 0.0f;
  s.materials.push_back(grey);
  s.meshes.push_back(m);
  scene::Node node;
  node.meshes = {0};
  s.nodes.push_back(node);
  s.roots = {0};
  s.instances.push_back({0, 0, glm::mat4(1.0f)});
  s.pose(0.0);
}

using VkSmoke = VkTracerTest;

TEST_F(VkSmoke, UniformSkyEqualsTheCpuTracer) {
  scene::Scene s;
  s.sidecar.environment = glm::vec3(0.25f, 1.0f, 4.0f);
  const ProbeGrid grid(Aabb{{-5.0f, -5.0f, -5.0f}, {5.0f, 5.0f, 5.0f}}, {2, 2, 2});
  const UpdateOptions options{.samples = 256, .seed = 9};
  ProbeVolume gpu_volume(grid, 2), cpu_volume(grid, 2);
  VkProbeTracer tracer(device(), s, {}, options);
  const probes::UpdateStats stats = tracer.update_all(gpu_volume);
  EXPECT_EQ(stats.rays, 8u * 256u);  // one escaping ray per path
  EXPECT_EQ(stats.probes_traced, 8u);
  trace::Tracer cpu(s);
  probes::TracerSource source(cpu);
  probes::ProbeTracer(source, options).update(cpu_volume);
  const float sqrt4pi = std::sqrt(4.0f * std::numbers::pi_v<float>);
  for (std::uint32_t p = 0; p < gpu_volume.probe_count(); ++p) {
    EXPECT_TRUE(gpu_volume.state(p).active());
    EXPECT_EQ(gpu_volume.state(p).updates, 1u);
    for (int i = 0; i < 9; ++i)
      for (int c = 0; c < 3; ++c) {
        const float L = s.sidecar.environment[c];
        // fp32 sums in another order: a few ulps of the L0 term.
        EXPECT_NEAR(gpu_volume.coefficients(p)[i][c], cpu_volume.coefficients(p)[i][c], 2e-5f * L * sqrt4pi)
            << "probe " << p << " coefficient " << i;
      }
  }
}

TEST_F(VkSmoke, EnvironmentMapWithNothingInTheWayEqualsTheCpuTracer) {
  // Every path is one escaping ray that reads the map: its conventions (rows, columns, the
  // rotation, the intensity) and bilinear lookup must be the CPU's.
  scene::Scene s;
  s.environment_map = test_environment_map();
  const ProbeGrid grid(Aabb{{-5.0f, -5.0f, -5.0f}, {5.0f, 5.0f, 5.0f}}, {2, 1, 1});
  const UpdateOptions options{.samples = 256, .seed = 5};
  ProbeVolume gpu_volume(grid, 2), cpu_volume(grid, 2);
  VkProbeTracer tracer(device(), s, {}, options);
  EXPECT_EQ(tracer.update_all(gpu_volume).rays, 2u * 256u);
  trace::Tracer cpu(s);
  probes::TracerSource source(cpu);
  probes::ProbeTracer(source, options).update(cpu_volume);
  for (std::uint32_t p = 0; p < gpu_volume.probe_count(); ++p) {
    ASSERT_TRUE(gpu_volume.state(p).active());
    // The sun (27 W m^-2 sr^-1 after the intensity) is in the coefficients. Differences come
    // from the GPU's trigonometry (Vulkan allows atan and acos 4096 ulps, about 5e-4 rad) at
    // the sun's edges, where the bilinear radiance changes by about 26 per texel (0.2 rad):
    // measured up to 1.1e-3 on lavapipe, against coefficients of 1-3. A wrong convention (a
    // mirrored u, the rotation's sign, rows upside down) moves the sun and is off by O(1).
    EXPECT_GT(cpu_volume.coefficients(p)[0].r, 1.0f);
    for (int i = 0; i < 9; ++i)
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(gpu_volume.coefficients(p)[i][c], cpu_volume.coefficients(p)[i][c], 4e-3f)
            << "probe " << p << " coefficient " << i << " channel " << c;
  }
}

TEST_F(VkSmoke, UpdatesLargerThanOneBatchGoInBatches) {
  // 2^21 paths per probe: a batch (4 Mi paths) holds two probes, so three take two batches.
  scene::Scene s;
  s.sidecar.environment = glm::vec3(1.0f, 2.0f, 0.5f);
  const ProbeGrid grid(Aabb{{0.0f, 0.0f, 0.0f}, {2.0f, 0.0f, 0.0f}}, {3, 1, 1});
  const UpdateOptions options{.samples = 1u << 21, .seed = 4};
  ProbeVolume gpu_volume(grid, 1), cpu_volume(grid, 1);
  VkProbeTracer tracer(device(), s, {}, options);
  const probes::UpdateStats stats = tracer.update_all(gpu_volume);
  EXPECT_EQ(stats.probes_traced, 3u);
  EXPECT_EQ(stats.rays, 3u << 21);
  trace::Tracer cpu(s);
  probes::TracerSource source(cpu);
  probes::ProbeTracer(source, options).update(cpu_volume);
  for (std::uint32_t p = 0; p < 3; ++p) {
    EXPECT_EQ(gpu_volume.state(p).updates, 1u) << p;
    for (int i = 0; i < 4; ++i)
      for (int c = 0; c < 3; ++c)  // two million fp32 terms summed in different orders
        EXPECT_NEAR(gpu_volume.coefficients(p)[i][c], cpu_volume.coefficients(p)[i][c], 1e-3f * s.sidecar.environment[c])
            << "probe " << p << " coefficient " << i;
  }
}

TEST_F(VkSmoke, ProbeInsideClosedBoxIsInactiveAndItsNeighbourIsNot) {
  scene::Scene s;
  s.sidecar.environment = glm::vec3(1.0f);
  add_box(s, glm::vec3(-1.0f), glm::vec3(1.0f));
  // Probe 0 at the box's centre, probe 1 two metres outside it.
  ProbeVolume volume(ProbeGrid(Aabb{{0.0f, 0.0f, 0.0f}, {3.0f, 0.0f, 0.0f}}, {2, 1, 1}), 2);
  VkProbeTracer tracer(device(), s, {}, UpdateOptions{.samples = 64, .seed = 1});
  const probes::UpdateStats first = tracer.update_all(volume);
  EXPECT_EQ(first.newly_inactive, 1u);
  EXPECT_TRUE(volume.state(0).inside_geometry());
  EXPECT_FLOAT_EQ(volume.state(0).backface_fraction, 1.0f);
  EXPECT_TRUE(volume.state(1).active());
  EXPECT_FALSE(volume.state(1).unclassified());
  for (const glm::vec3& c : volume.coefficients(0)) EXPECT_EQ(c, glm::vec3(0.0f));
  // The sky reaches probe 1 from every direction but the box's: L0 below that of the open sky.
  const float open = std::sqrt(4.0f * std::numbers::pi_v<float>);
  EXPECT_GT(volume.coefficients(1)[0].x, 0.5f * open);
  EXPECT_LT(volume.coefficients(1)[0].x, 0.99f * open);
  const probes::UpdateStats second = tracer.update_all(volume);
  EXPECT_EQ(second.probes_traced, 1u);  // the inside probe is not traced again
  EXPECT_EQ(volume.state(1).updates, 2u);
  // The GPU's running average is the host volume's.
  const auto gpu = tracer.coefficient_buffer().read<glm::vec3>(volume.all_coefficients().size());
  for (std::size_t i = 0; i < gpu.size(); ++i) EXPECT_EQ(gpu[i], volume.all_coefficients()[i]) << i;
}

}  // namespace
}  // namespace ddish::trace_vk::test
