// Stiff and extreme cases of the probe module (docs/extreme-cases.md): 1x1x1 and 64x64x64
// grids, every probe inside geometry, hysteresis 0 and 1, a probe exactly on a surface, and the
// running average that fp16 storage would stall. The 1e6 emitter: test_probes_traced.cpp
// (ProbesTraced.BrightEmitterPacksWithoutSilentOverflow) and test_volume_packing_file.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>

#include "probes/accumulation.h"
#include "probes/probe_tracer.h"
#include "probes/tracer_source.h"
#include "probes/volume_packing.h"
#include "scene/scene.h"
#include "sh/packing.h"
#include "synthetic_sources.h"
#include "trace/tracer.h"

using namespace ddish::probes;
using ddish::scene::Aabb;
using ddish::trace::PathSample;
using ddish::trace::Ray;
using ddish::trace::Sampler;

namespace {

const float kSqrt4Pi = std::sqrt(4.0f * std::numbers::pi_v<float>);

}  // namespace

// One probe: a zero-extent box is allowed, the probe sits at its point, every world position
// maps to grid coordinate 0 (no division by the zero spacing), and an update gives the
// analytic L0 of a uniform environment.
TEST(ExtremeProbes, OneProbeGridUpdatesAndMapsEverythingToIt) {
  const ProbeGrid grid(Aabb{{2.0f, 3.0f, 4.0f}, {2.0f, 3.0f, 4.0f}}, {1, 1, 1});
  EXPECT_EQ(grid.probe_count(), 1u);
  EXPECT_EQ(grid.position(0u), glm::vec3(2.0f, 3.0f, 4.0f));
  EXPECT_EQ(grid.spacing(), glm::vec3(0.0f));
  for (const glm::vec3& p : {glm::vec3(-1e6f), glm::vec3(2.0f, 3.0f, 4.0f), glm::vec3(1e30f)})
    EXPECT_EQ(grid.grid_coordinate(p), glm::vec3(0.0f));
  ProbeVolume volume(grid, 2);
  synthetic::FunctionSource source([](const Ray&, Sampler&) { return synthetic::uniform(glm::vec3(0.5f)); });
  const UpdateStats stats = ProbeTracer(source, UpdateOptions{.samples = 64}).update(volume);
  EXPECT_EQ(stats.probes_traced, 1u);
  EXPECT_NEAR(volume.sh(0)[0].x, 0.5f * kSqrt4Pi, 1e-5f);
  // A 1x1x1 grid over a real box: the probe is the box centre.
  const ProbeGrid box(Aabb{{-1.0f, 0.0f, 2.0f}, {3.0f, 2.0f, 4.0f}}, {1, 1, 1});
  EXPECT_EQ(box.position(0u), glm::vec3(1.0f, 1.0f, 3.0f));
}

// 64^3 = 262,144 probes: the index arithmetic holds at the far corner, the fp32 volume holds
// 262,144 x 9 x 12 B = 28.3 MB of coefficients, and the packed form 56 B a probe = 14.7 MB
// (14,680,064 bytes, what the wire and a volume file carry; on the GPU the same 56 B a probe in
// seven RGBA16F textures, extreme_raster_test.cpp). Updating only the eight corner probes
// touches nothing else.
TEST(ExtremeProbes, SixtyFourCubedGridSizesAndCornerUpdates) {
  const ProbeGrid grid(Aabb{{0.0f, 0.0f, 0.0f}, {64.0f, 64.0f, 64.0f}}, {64, 64, 64});
  ASSERT_EQ(grid.probe_count(), 262144u);
  EXPECT_EQ(grid.index({63, 63, 63}), 262143u);
  EXPECT_EQ(grid.cell(262143u), glm::ivec3(63));
  EXPECT_EQ(grid.position(262143u), glm::vec3(63.5f));
  EXPECT_EQ(grid.grid_coordinate(glm::vec3(63.5f)), glm::vec3(63.0f));
  ProbeVolume volume(grid, 2);
  EXPECT_EQ(volume.all_coefficients().size_bytes(), 262144u * 9u * 12u);
  std::vector<std::uint32_t> corners;
  for (int c = 0; c < 8; ++c)
    corners.push_back(grid.index({(c & 1) ? 63 : 0, (c & 2) ? 63 : 0, (c & 4) ? 63 : 0}));
  synthetic::FunctionSource source([](const Ray& r, Sampler&) {
    return synthetic::uniform(glm::vec3(1.0f + 0.01f * r.origin.x));
  });
  const UpdateStats stats = ProbeTracer(source, UpdateOptions{.samples = 32}).update(volume, corners);
  EXPECT_EQ(stats.probes_traced, 8u);
  for (std::uint32_t i : corners)
    EXPECT_NEAR(volume.sh(i)[0].x, (1.0f + 0.01f * grid.position(i).x) * kSqrt4Pi, 1e-4f) << i;
  EXPECT_EQ(volume.state(grid.index({1, 0, 0})).updates, 0u);
  const PackedVolume packed = pack_volume(volume);
  EXPECT_EQ(packed.bytes(), 14680064u);
  EXPECT_EQ(packed.status, ddish::sh::PackStatus::kOk);
  EXPECT_EQ(packed.half_probes, 262144u);
  EXPECT_NEAR(unpack_probe(packed, corners.back())[0].x, volume.sh(corners.back())[0].x, 2e-3f);
}

// Every probe inside geometry (every first hit a back face): all become inactive on their
// first update with zero coefficients (so even an interpolation that ignored the flag adds
// nothing), later updates trace no rays, and the packed volume carries the inactive flag and
// zeros. The rasterizer's side (zero indirect, no NaN from a zero weight sum):
// extreme_raster_test.cpp.
TEST(ExtremeProbes, EveryProbeInsideGeometryIsInactiveAndZero) {
  synthetic::FunctionSource source([](const Ray&, Sampler&) {
    PathSample s;
    s.radiance = glm::vec3(3.0f);  // light leaking through the backs of faces
    s.hit = true;
    s.backface = true;
    s.hit_distance = 0.1f;
    return s;
  });
  ProbeVolume volume(ProbeGrid(Aabb{{0, 0, 0}, {2, 2, 2}}, {2, 2, 2}));
  ProbeTracer tracer(source, UpdateOptions{.samples = 64});
  const UpdateStats first = tracer.update(volume);
  EXPECT_EQ(first.newly_inactive, 8u);
  EXPECT_EQ(volume.active_count(), 0u);
  EXPECT_EQ(volume.inside_geometry_count(), 8u);
  for (std::uint32_t p = 0; p < 8; ++p) {
    EXPECT_FLOAT_EQ(volume.state(p).backface_fraction, 1.0f);
    for (const glm::vec3& c : volume.coefficients(p)) EXPECT_EQ(c, glm::vec3(0.0f));
  }
  const std::uint64_t rays = source.rays_traced();
  const UpdateStats second = tracer.update(volume);
  EXPECT_EQ(second.probes_traced, 0u);
  EXPECT_EQ(source.rays_traced(), rays);
  const PackedVolume packed = pack_volume(volume);
  for (std::uint32_t p = 0; p < 8; ++p) {
    EXPECT_TRUE(unpack_flags(packed, p) & kProbeInactive);
    const ddish::sh::ShRgb s = unpack_probe(packed, p);
    for (int i = 0; i < s.count(); ++i) EXPECT_EQ(s[i], glm::vec3(0.0f));
  }
}

// Hysteresis 0: every update replaces the average (w = max(1/k, 1) = 1). Hysteresis 1 would
// freeze a probe after its first update forever (w = max(1/k, 0) -> 0 is the exact mean, and
// never forgets): it is rejected, as are values outside [0, 1) and NaN, with the value named.
TEST(ExtremeProbes, HysteresisZeroReplacesAndOneIsRejected) {
  ProbeVolume volume;
  for (float e : {5.0f, -2.0f, 7.25f}) {
    ddish::sh::ShRgb est(2);
    est[0] = glm::vec3(e);
    volume.accumulate(0, est, 16, 0.0f);
    EXPECT_EQ(volume.sh(0)[0].x, e);
  }
  EXPECT_EQ(blend_weight(1000000u, 0.0f), 1.0f);
  for (float bad : {1.0f, 1.5f, -0.01f, std::nanf("")}) {
    try {
      check_hysteresis(bad);
      ADD_FAILURE() << "hysteresis " << bad << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()).rfind("hysteresis must be in [0, 1), got ", 0), 0u) << e.what();
    }
  }
  try {
    check_hysteresis(1.0f);
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "hysteresis must be in [0, 1), got 1.000000");
  }
  synthetic::FunctionSource source([](const Ray&, Sampler&) { return synthetic::uniform(glm::vec3(1.0f)); });
  EXPECT_THROW(ProbeTracer(source, UpdateOptions{.hysteresis = 1.0f}), std::invalid_argument);
  // The largest float below 1 is accepted and still blends (w = 1 - alpha = 6e-8 > 0 once the
  // 1/k phase is over; fp32 represents it, an fp16 average would not: see the stall test).
  EXPECT_NO_THROW(check_hysteresis(std::nextafter(1.0f, 0.0f)));
  EXPECT_GT(blend_weight(1u << 30, std::nextafter(1.0f, 0.0f)), 0.0f);
}

// A probe exactly on a single-sided floor (y = 0, facing +y), with the path tracer: rays start
// at tmin 0 on the plane. The upper hemisphere sees the sky; every ray of the lower hemisphere
// hits the floor at t = 0 from behind (Embree takes hits with t >= tmin), so the probe sees the
// floor's back over half its sphere (fraction ~0.5 > 0.25) and is classified inside geometry:
// inactive, zero coefficients, zero weight in interpolation. That is the conservative side:
// its upper half is valid but its lower half would bleed the black underside of the floor into
// the floor's own lighting. Probes are placed at cell centres, half a cell inside the bounds, so
// this happens only when a surface runs through a row of cell centres, and the neighbouring
// probes above take over.
TEST(ExtremeProbes, ProbeExactlyOnASurfaceSeesItsBackAndIsInactive) {
  ddish::scene::Scene s;
  s.sidecar.environment = glm::vec3(1.0f);
  ddish::scene::Mesh floor;
  floor.positions = {{-5, 0, -5}, {-5, 0, 5}, {5, 0, 5}, {5, 0, -5}};
  floor.normals.assign(4, {0, 1, 0});
  floor.uvs.assign(4, glm::vec2(0.0f));
  floor.tangents.assign(4, {1, 0, 0, 1});
  floor.indices = {0, 1, 2, 0, 2, 3};  // counter-clockwise seen from +y
  for (const glm::vec3& p : floor.positions) floor.bounds.expand(p);
  floor.material = 0;
  ddish::scene::Material grey;
  grey.base_color = glm::vec4(0.5f, 0.5f, 0.5f, 1.0f);
  grey.metallic = 0.0f;
  s.materials.push_back(grey);
  s.meshes.push_back(floor);
  ddish::scene::Instance inst;
  inst.mesh = 0;
  s.instances.push_back(inst);
  ddish::trace::Tracer tracer(s);
  TracerSource source(tracer);
  // Probe 1 of three along y over [-1.5, 1.5] sits at y = 0 exactly.
  ProbeVolume volume(ProbeGrid(Aabb{{-0.5f, -1.5f, -0.5f}, {0.5f, 1.5f, 0.5f}}, {1, 3, 1}));
  ASSERT_EQ(volume.grid().position(1u).y, 0.0f);
  ProbeTracer(source, UpdateOptions{.samples = 256, .seed = 3}).update(volume);
  const ddish::sh::ShRgb on = volume.sh(1);
  ASSERT_TRUE(all_finite(on));
  EXPECT_FALSE(volume.state(1).active());
  EXPECT_TRUE(volume.state(1).inside_geometry());
  EXPECT_NEAR(volume.state(1).backface_fraction, 0.5f, 0.05f);
  for (int i = 0; i < on.count(); ++i) EXPECT_EQ(on[i], glm::vec3(0.0f));
  // For contrast, the probe 1.5 m below the 10 m floor sees its back over less than half its
  // sphere but more than a quarter (inside geometry too), and the one above sees the floor's
  // front: active, its L0 between the sky's upper half alone (0.5 sqrt(4 pi)) and sky all round
  // (the floor below, albedo 0.5, returns less than the sky it reflects).
  EXPECT_FALSE(volume.state(0).active());
  EXPECT_GT(volume.state(0).backface_fraction, 0.25f);
  EXPECT_LT(volume.state(0).backface_fraction, 0.5f);
  EXPECT_TRUE(volume.state(2).active());
  EXPECT_EQ(volume.state(2).backface_fraction, 0.0f);
  EXPECT_GT(volume.sh(2)[0].x, 0.5f * kSqrt4Pi);
  EXPECT_LT(volume.sh(2)[0].x, kSqrt4Pi);
  EXPECT_TRUE(all_finite(volume.sh(2)));
}

// fp16 would stall the running average: with alpha = 0.99 each update moves the average by
// 0.01 (e - A). Stored in fp16 between 1 and 2, one ulp is 2^-10 = 9.8e-4, so an update rounds
// to no change whenever 0.01 |e - A| is below half an ulp, i.e. whenever |e - A| < 0.049. A
// probe that held 1.1 when its light was dimmed to 1.0 (noise 0.005) walks down only until it
// is 0.049 above the new value less the noise, then stops for good. The fp32 average
// (ProbeVolume::accumulate, the project's) represents the 1e-4-sized steps and converges.
TEST(ExtremeProbes, Fp16RunningAverageStallsWhereFp32Converges) {
  constexpr float kAlpha = 0.99f, kMean = 1.0f, kSigma = 0.005f, kStart = 1.1f;
  std::mt19937 rng(17);
  std::normal_distribution<float> noise(0.0f, kSigma);
  ProbeVolume volume;
  ddish::sh::ShRgb start(2);
  start[0] = glm::vec3(kStart);
  // The history: a converged probe (many updates) holding the old value 1.1.
  volume.accumulate(0, start, 256, kAlpha);
  volume.state(0).updates = 1000;
  std::uint16_t half = ddish::sh::float_to_half(kStart);
  double last_fp32 = 0.0, last_fp16 = 0.0;
  int fp16_changes = 0;
  const int kUpdates = 2000;
  double fp32_tail = 0.0, fp16_tail = 0.0;
  for (int k = 0; k < kUpdates; ++k) {
    const float e = kMean + noise(rng);
    ddish::sh::ShRgb est(2);
    est[0] = glm::vec3(e);
    volume.accumulate(0, est, 256, kAlpha);
    // The same blend with the average stored as fp16 between updates.
    const float a = ddish::sh::half_to_float(half);
    const std::uint16_t next = ddish::sh::float_to_half(a + (1.0f - kAlpha) * (e - a));
    if (next != half) ++fp16_changes;
    half = next;
    last_fp32 = volume.sh(0)[0].x;
    last_fp16 = ddish::sh::half_to_float(half);
    if (k >= kUpdates - 500) {
      fp32_tail += last_fp32 / 500.0;
      fp16_tail += last_fp16 / 500.0;
    }
  }
  std::printf("[extreme] after %d updates from %.2f towards %.2f: fp32 %.5f, fp16 %.5f "
              "(fp16 changed %d times)\n",
              kUpdates, double(kStart), double(kMean), last_fp32, last_fp16, fp16_changes);
  // fp32: the exponential average of noise sigma 0.005 has a standard deviation of
  // sigma sqrt((1 - alpha) / (1 + alpha)) = 3.5e-4 and the 0.1 step has decayed by
  // 0.99^2000 = 2e-9: within 4 sigma = 1.5e-3 of the mean.
  EXPECT_NEAR(last_fp32, kMean, 1.5e-3);
  EXPECT_NEAR(fp32_tail, kMean, 1.5e-3);
  // fp16: stuck 0.025 or more above the mean (0.049 less a few sigma of noise; 0.032 seen),
  // 17 times the fp32 bound, after changing only a few dozen times in 2000 updates.
  EXPECT_GT(last_fp16 - kMean, 0.025);
  EXPECT_GT(fp16_tail - kMean, 0.025);
  EXPECT_LT(fp16_changes, 100);
}
