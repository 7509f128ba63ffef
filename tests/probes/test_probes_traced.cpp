// Probe updates with the real path tracer on small scenes built in memory: an empty scene with
// a uniform sky, a closed single-sided box (probe inside = back faces = inactive), and a
// 1e6-radiance emitter (packing switches to shared exponent, never Inf).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>

#include "probes/probe_tracer.h"
#include "probes/tracer_source.h"
#include "probes/volume_packing.h"
#include "scene/scene.h"
#include "trace/tracer.h"

using namespace ddish::probes;
using ddish::scene::Aabb;
using ddish::scene::Scene;

namespace {

// Adds a mesh of quads (4 corners each, counter-clockwise seen from the front, as glTF
// defines front faces) with one material, as one instance.
void add_quads(Scene& s, const std::vector<std::array<glm::vec3, 4>>& quads,
               const ddish::scene::Material& material) {
  ddish::scene::Mesh mesh;
  for (const auto& q : quads) {
    const glm::vec3 n = glm::normalize(glm::cross(q[1] - q[0], q[2] - q[0]));
    const auto base = std::uint32_t(mesh.positions.size());
    for (const glm::vec3& p : q) {
      mesh.positions.push_back(p);
      mesh.normals.push_back(n);
      mesh.uvs.emplace_back(0.0f);
      mesh.tangents.emplace_back(1.0f, 0.0f, 0.0f, 1.0f);
      mesh.bounds.expand(p);
    }
    for (std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) mesh.indices.push_back(base + i);
  }
  mesh.material = int(s.materials.size());
  s.materials.push_back(material);
  s.meshes.push_back(mesh);
  ddish::scene::Instance inst;
  inst.mesh = int(s.meshes.size()) - 1;
  s.instances.push_back(inst);
}

// A closed box whose faces point outwards (single-sided): seen from inside, every face is a
// back face.
void add_box(Scene& s, const glm::vec3& lo, const glm::vec3& hi) {
  auto corner = [&](int i) {
    return glm::vec3((i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z);
  };
  // Each face: its four corners in order around it.
  const int faces[6][4] = {{0, 2, 6, 4}, {1, 3, 7, 5}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  std::vector<std::array<glm::vec3, 4>> quads;
  const glm::vec3 centre = 0.5f * (lo + hi);
  for (const auto& f : faces) {
    std::array<glm::vec3, 4> q = {corner(f[0]), corner(f[1]), corner(f[2]), corner(f[3])};
    // Make the winding's normal point away from the box centre whatever the table says.
    const glm::vec3 n = glm::cross(q[1] - q[0], q[2] - q[0]);
    const glm::vec3 mid = 0.25f * (q[0] + q[1] + q[2] + q[3]);
    if (glm::dot(n, mid - centre) < 0.0f) std::swap(q[1], q[3]);
    quads.push_back(q);
  }
  ddish::scene::Material grey;
  grey.base_color = glm::vec4(0.5f, 0.5f, 0.5f, 1.0f);
  grey.metallic = 0.0f;
  add_quads(s, quads, grey);
}

}  // namespace

TEST(ProbesTraced, EmptySceneUniformSkyIsAnalyticL0) {
  Scene s;
  s.sidecar.environment = glm::vec3(0.25f, 1.0f, 4.0f);
  ddish::trace::Tracer tracer(s);
  TracerSource source(tracer);
  ProbeVolume volume(ProbeGrid(Aabb{{-5.0f, -5.0f, -5.0f}, {5.0f, 5.0f, 5.0f}}, {2, 2, 2}), 2);
  UpdateStats stats = ProbeTracer(source, UpdateOptions{.samples = 256, .seed = 9}).update(volume);
  EXPECT_EQ(stats.rays, 8u * 256u);  // one escaping ray per path
  EXPECT_EQ(volume.active_count(), 8u);
  const float sqrt4pi = std::sqrt(4.0f * std::numbers::pi_v<float>);
  for (std::uint32_t p = 0; p < volume.probe_count(); ++p) {
    ddish::sh::ShRgb c = volume.sh(p);
    for (int ch = 0; ch < 3; ++ch) {
      const float L = s.sidecar.environment[ch];
      EXPECT_NEAR(c[0][ch], L * sqrt4pi, 2e-6f * L * sqrt4pi);
      // Bands 1-2 of a 256-point lattice: below 5e-3 L for any rotation (test_probe_update).
      for (int i = 1; i < 9; ++i) EXPECT_LT(std::abs(c[i][ch]), 5e-3f * L) << i;
    }
  }
}

TEST(ProbesTraced, ProbeInsideClosedBoxIsInactiveAndNotTracedAgain) {
  Scene s;
  s.sidecar.environment = glm::vec3(1.0f);
  add_box(s, glm::vec3(-1.0f), glm::vec3(1.0f));
  ddish::trace::Tracer tracer(s);
  TracerSource source(tracer);
  // Three probes along x, at x = -2.5, 0 and 2.5 (counts 3 over [-3.75, 3.75]): the middle one
  // inside the box [-1, 1]^3, the others outside it.
  ProbeVolume volume(ProbeGrid(Aabb{{-3.75f, -0.5f, -0.5f}, {3.75f, 0.5f, 0.5f}}, {3, 1, 1}));
  const std::uint32_t inside = 1;
  ASSERT_EQ(volume.grid().position(inside), glm::vec3(0.0f));
  ProbeTracer probe_tracer(source, UpdateOptions{.samples = 128});
  UpdateStats first = probe_tracer.update(volume);
  EXPECT_EQ(first.newly_inactive, 1u);
  EXPECT_FALSE(volume.state(inside).active());
  EXPECT_TRUE(volume.state(inside).inside_geometry());
  EXPECT_FLOAT_EQ(volume.state(inside).backface_fraction, 1.0f);
  for (const glm::vec3& c : volume.coefficients(inside)) EXPECT_EQ(c, glm::vec3(0.0f));
  for (std::uint32_t p : {0u, 2u}) {
    EXPECT_TRUE(volume.state(p).active()) << p;
    EXPECT_EQ(volume.state(p).backface_fraction, 0.0f) << p;
    EXPECT_GT(volume.coefficients(p)[0].x, 0.0f) << p;
  }
  // The inactive probe casts no more rays: a second update costs the two outside probes only.
  tracer.reset_ray_count();
  UpdateStats second = probe_tracer.update(volume);
  EXPECT_EQ(second.probes_traced, 2u);
  EXPECT_EQ(second.paths, 2u * 128u);
  std::vector<std::uint32_t> only_inside = {inside};
  EXPECT_EQ(probe_tracer.update(volume, only_inside).rays, 0u);
  EXPECT_EQ(volume.state(inside).updates, 0u);
}

TEST(ProbesTraced, BrightEmitterPacksWithoutSilentOverflow) {
  Scene s;
  // A 2 x 2 m emitter of radiance 1e6 facing a probe 0.5 m away (3.7 sr of its sphere):
  // L0 ~ 1e6 · 3.7 sr · 0.28 ~ 1e6, fifteen times fp16's largest value.
  ddish::scene::Material light;
  light.base_color = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  light.emissive = glm::vec3(1.0f);
  light.emissive_strength = 1e6f;
  add_quads(s, {{glm::vec3(-1.0f, -1.0f, 1.0f), glm::vec3(-1.0f, 1.0f, 1.0f),
                 glm::vec3(1.0f, 1.0f, 1.0f), glm::vec3(1.0f, -1.0f, 1.0f)}},
            light);  // counter-clockwise seen from -z: faces the probes
  ddish::trace::Tracer tracer(s);
  TracerSource source(tracer);
  // Probe 1 at z = 0.5, next to the emitter (it subtends 3.7 sr there); probe 0 at z = -19.5,
  // 20.5 m away (0.01 sr: L0 of a few thousand, within fp16).
  ProbeVolume volume(ProbeGrid(Aabb{{-0.5f, -0.5f, -29.5f}, {0.5f, 0.5f, 10.5f}}, {1, 1, 2}));
  const std::uint32_t near_probe = 1, far_probe = 0;
  ASSERT_NEAR(volume.grid().position(near_probe).z, 0.5f, 1e-4f);
  ASSERT_NEAR(volume.grid().position(far_probe).z, -19.5f, 1e-4f);
  ProbeTracer(source, UpdateOptions{.samples = 512}).update(volume);
  ddish::sh::ShRgb c = volume.sh(near_probe);
  ASSERT_GT(c[0].x, 2.0f * ddish::sh::kHalfMax);

  std::uint16_t words[ddish::sh::packed_words(2)];
  EXPECT_EQ(ddish::sh::pack_half(c, 0, words), ddish::sh::PackStatus::kOverflow);

  PackedVolume packed = pack_volume(volume);
  EXPECT_EQ(packed.status, ddish::sh::PackStatus::kOk);
  EXPECT_EQ(packed.encoding, Encoding::kMixed);
  EXPECT_EQ(ddish::sh::packed_format(packed.probe(near_probe), 2), ddish::sh::PackFormat::kSharedExp);
  EXPECT_EQ(ddish::sh::packed_format(packed.probe(far_probe), 2), ddish::sh::PackFormat::kHalf);
  ddish::sh::ShRgb back = unpack_probe(packed, near_probe);
  for (int ch = 0; ch < 3; ++ch) {
    float channel_max = 0.0f;
    for (int j = 0; j < 9; ++j) channel_max = std::max(channel_max, std::abs(c[j][ch]));
    for (int j = 0; j < 9; ++j) {
      ASSERT_TRUE(std::isfinite(back[j][ch]));
      EXPECT_NEAR(back[j][ch], c[j][ch], channel_max / 16383.0f) << j;
    }
  }
}

TEST(ProbesTraced, SameSeedSameCoefficientsWithTheTracer) {
  // Diffuse bounces off a box under a sky: every path is noisy, so equal results mean equal
  // random numbers.
  Scene s;
  s.sidecar.environment = glm::vec3(1.0f, 0.8f, 0.6f);
  add_box(s, glm::vec3(-1.0f), glm::vec3(1.0f));
  ddish::trace::Tracer tracer(s);
  TracerSource source(tracer);
  auto run = [&](std::uint64_t seed) {
    ProbeVolume v(ProbeGrid(Aabb{{-3.0f, 1.5f, -3.0f}, {3.0f, 2.5f, 3.0f}}, {2, 1, 2}));
    ProbeTracer t(source, UpdateOptions{.samples = 64, .seed = seed});
    t.update(v);
    t.update(v);
    return v;
  };
  ProbeVolume a = run(21), b = run(21), c = run(22);
  auto ca = a.all_coefficients(), cb = b.all_coefficients(), cc = c.all_coefficients();
  ASSERT_EQ(ca.size(), cb.size());
  EXPECT_EQ(std::memcmp(ca.data(), cb.data(), ca.size_bytes()), 0);
  EXPECT_NE(std::memcmp(ca.data(), cc.data(), ca.size_bytes()), 0);
}
