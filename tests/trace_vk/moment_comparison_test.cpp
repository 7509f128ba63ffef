// The GPU probe tracer's distance moments (probe_project.comp) against the Embree tracer's
// (probes::MomentEstimate), statistically over every texel of every probe of a small grid, as
// statistical_comparison.h compares SH: each tracer fills R fresh volumes once (so each texel's
// value is one update's estimate), and every (probe, texel, moment) term gets Welch's z. The
// probes sit at deliberately relocated positions (ProbeVolume::set_offset), which both tracers
// must trace from. The paths stop at their first hit (max_bounces 0): distances need nothing
// else, and it keeps the test cheap on lavapipe.
//
// Thresholds as in embree_comparison_test.cpp: R = 16, so each z is close to Student's t with
// 30 degrees of freedom (mean z^2 = 1.07); mean z^2 < 1.6 and max |z| < 5.5 over several hundred
// terms. Each test also shows that the GPU's data under a wrong convention, or the CPU's traced
// from the grid positions instead of the relocated ones, fails the same test by far.
//
// Relocation (UpdateOptions::relocate): with the same seed both tracers draw the same rotations,
// and a first hit depends only on the ray, so a probe inside a closed sphere moves to the same
// offset on both, and comes out active: its update traced from where it moved.
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>

#include <gtest/gtest.h>

#include "../raster/raster_scenes.h"
#include "probes/probe_grid.h"
#include "probes/probe_tracer.h"
#include "probes/tracer_source.h"
#include "scene/gltf_loader.h"
#include "scene/scene.h"
#include "statistical_comparison.h"
#include "trace/tracer.h"
#include "trace_vk/vk_probe_tracer.h"
#include "vk_test.h"

namespace ddish::trace_vk::test {
namespace {

constexpr int kUpdates = 16;
constexpr int kResolution = 8;  // the default --probe-visibility
constexpr std::uint32_t kSamples = 512;

// A fixed offset per probe within the relocation bound: a different direction for each.
glm::vec3 offset_of(const probes::ProbeGrid& grid, std::uint32_t p) {
  const glm::vec3 u(std::sin(1.7f * float(p) + 0.3f), std::sin(2.9f * float(p) + 1.1f), std::sin(4.3f * float(p) + 2.3f));
  return 0.3f * u * grid.spacing();
}

// R single-update estimates of every probe's moments: [probe][update][texel * 2 + moment].
Estimates single_update_moments(const probes::ProbeUpdater& updater, const probes::ProbeGrid& grid, bool offsets) {
  Estimates e;
  e.values.resize(grid.probe_count());
  for (int r = 0; r < kUpdates; ++r) {
    probes::ProbeVolume volume(grid, 1, kResolution);
    volume.set_frame(std::uint64_t(1000 + 2 * r));  // fresh rotations for every estimate
    if (offsets)
      for (std::uint32_t p = 0; p < volume.probe_count(); ++p) volume.set_offset(p, offset_of(grid, p));
    updater.update_all(volume);
    for (std::uint32_t p = 0; p < volume.probe_count(); ++p) {
      if (!volume.state(p).active()) continue;
      std::vector<double> v;
      for (const glm::vec2& m : volume.moments(p)) v.insert(v.end(), {double(m.x), double(m.y)});
      e.values[p].push_back(std::move(v));
    }
  }
  return e;
}

// The same estimates through a per-texel change of convention (mean d, mean d^2) -> ...
Estimates transformed(Estimates e, const std::function<glm::dvec2(glm::dvec2)>& f) {
  for (auto& probe : e.values)
    for (auto& update : probe)
      for (std::size_t t = 0; t + 1 < update.size(); t += 2) {
        const glm::dvec2 m = f({update[t], update[t + 1]});
        update[t] = m.x;
        update[t + 1] = m.y;
      }
  return e;
}

// The test: both tracers' moments agree within Monte Carlo error (the worst term is named as
// compare() names SH terms: "coefficient" is the texel * 2 + moment).
bool passes(const Comparison& c) { return c.mean_z2 < 1.6 && c.max_abs_z < 5.5; }

class VkMomentsVersusEmbree : public VkTracerTest {
 protected:
  void check(const scene::Scene& s, const probes::ProbeGrid& grid, int min_terms) {
    trace::PathOptions path;
    path.max_bounces = 0;
    const probes::UpdateOptions gpu_options{.samples = kSamples, .hysteresis = 0.0f, .seed = 505};
    const probes::UpdateOptions cpu_options{.samples = kSamples, .hysteresis = 0.0f, .seed = 606};
    const VkProbeTracer gpu(device(), s, path, gpu_options);
    trace::Tracer cpu(s, path);
    const probes::TracerSource source(cpu);
    const probes::ProbeTracer cpu_tracer(source, cpu_options);
    const Estimates a = single_update_moments(gpu, grid, true);
    const Estimates b = single_update_moments(cpu_tracer, grid, true);
    const Comparison c = compare(a, b, 1.0);
    EXPECT_GE(c.terms, min_terms);
    EXPECT_EQ(c.classified_apart, 0);
    EXPECT_TRUE(passes(c)) << c.terms << " terms over " << c.probes << " probes: mean z^2 " << c.mean_z2
                           << ", max |z| " << c.max_abs_z << "; worst " << c.worst;
    std::printf("%d terms over %d probes: mean z^2 %.3f, max |z| %.2f (%s)\n", c.terms, c.probes, c.mean_z2,
                c.max_abs_z, c.worst.c_str());

    // What the test would see of a wrong convention on the GPU's side, or of probes traced from
    // their grid positions on the CPU's.
    const double range = probes::ProbeVolume(grid, 1, kResolution).moment_range();
    const Comparison unscaled = compare(transformed(a, [&](glm::dvec2 m) { return m * glm::dvec2(range, range * range); }), b, 1.0);
    const Comparison squared = compare(transformed(a, [](glm::dvec2 m) { return glm::dvec2(m.x, m.x * m.x); }), b, 1.0);
    const Comparison unmoved = compare(a, single_update_moments(cpu_tracer, grid, false), 1.0);
    EXPECT_FALSE(passes(unscaled)) << "distances not divided by the range would pass";
    EXPECT_FALSE(passes(squared)) << "the square of the mean for the mean square would pass";
    EXPECT_FALSE(passes(unmoved)) << "probes traced from their grid positions would pass";
    std::printf("wrong conventions: not divided by the range mean z^2 %.1f; (mean d)^2 for mean d^2 %.2f (max |z| "
                "%.1f); grid positions %.1f\n",
                unscaled.mean_z2, squared.mean_z2, squared.max_abs_z, unmoved.mean_z2);
  }
};

TEST_F(VkMomentsVersusEmbree, CornellBoxFromRelocatedProbes) {
  const scene::Scene s = scene::load_scene(std::string(DDISH_SOURCE_DIR) + "/scenes/cornell_box.gltf");
  const glm::vec3 d = (s.bounds().max - s.bounds().min) * 0.15f;
  const probes::ProbeGrid grid(scene::Aabb{s.bounds().min + d, s.bounds().max - d}, {3, 3, 3});
  check(s, grid, 27 * kResolution * kResolution);
}

TEST_F(VkMomentsVersusEmbree, SphereOverGroundWithMissesFromRelocatedProbes) {
  // Open to the sky: many rays miss (a miss counts as the range), others hit the ground or the
  // sphere within it or beyond it (clamped).
  const scene::Scene s = raster::test::sphere_over_ground(0.5f);
  const probes::ProbeGrid grid(scene::Aabb{{-1.2f, 0.3f, -1.2f}, {1.2f, 1.5f, 1.2f}}, {3, 2, 3});
  check(s, grid, 18 * kResolution * kResolution / 2);
}

// A closed, single-sided UV sphere (faces outwards) around (1.7, 1.5, 1.5): probe 13 of a
// 3 x 3 x 3 grid over [0, 3]^3 sits inside it, 0.1 m from its -x side.
TEST_F(VkMomentsVersusEmbree, RelocationMovesAProbeOutOfASphereAsTheCpuDoes) {
  scene::Scene s = raster::test::one_mesh_scene(raster::test::uv_sphere(0.3f, 48, 24),
                                                raster::test::make_material({0.7f, 0.7f, 0.7f}, 0.0f, 0.8f));
  s.nodes[0].translation = glm::vec3(1.7f, 1.5f, 1.5f);
  s.pose(0.0);
  s.sidecar.environment = glm::vec3(0.5f, 0.6f, 0.8f);
  const probes::ProbeGrid grid(scene::Aabb{glm::vec3(0.0f), glm::vec3(3.0f)}, {3, 3, 3});
  ASSERT_EQ(grid.position(13), glm::vec3(1.5f));
  trace::PathOptions path;
  path.max_bounces = 1;
  const probes::UpdateOptions options{.samples = 128, .seed = 7, .relocate = true};
  const VkProbeTracer gpu(device(), s, path, options);
  trace::Tracer cpu(s, path);
  const probes::TracerSource source(cpu);
  const probes::ProbeTracer cpu_tracer(source, options);
  probes::ProbeVolume on_gpu(grid, 2, kResolution), on_cpu(grid, 2, kResolution);
  gpu.update_all(on_gpu);
  cpu_tracer.update_all(on_cpu);

  EXPECT_TRUE(on_gpu.state(13).active()) << "traced from where it moved, it is outside the sphere";
  EXPECT_LT(on_gpu.position(13).x, 1.4f) << "out through the near side";
  EXPECT_EQ(on_gpu.inactive_count(), 0u);
  for (std::uint32_t p = 0; p < grid.probe_count(); ++p) {
    EXPECT_EQ(on_gpu.state(p).active(), on_cpu.state(p).active()) << p;
    EXPECT_NEAR(glm::length(on_gpu.offset(p) - on_cpu.offset(p)), 0.0f, 1e-3f) << "probe " << p;
  }
  // Its moments are seen from outside: towards +x the sphere's near side, about 0.1 m away.
  const glm::vec2 toward = on_gpu.moments(13)[probes::moment_texel({1, 0, 0}, kResolution)];
  EXPECT_LT(toward.x * on_gpu.moment_range(), 0.2f);
  std::printf("probe 13 moved by (%.3f, %.3f, %.3f) on the GPU, (%.3f, %.3f, %.3f) on the CPU\n", on_gpu.offset(13).x,
              on_gpu.offset(13).y, on_gpu.offset(13).z, on_cpu.offset(13).x, on_cpu.offset(13).y, on_cpu.offset(13).z);
}

}  // namespace
}  // namespace ddish::trace_vk::test
