// The change-driven stream: what the server publishes (PublishedProbes) and what a client's
// mirror makes of it (ProbeMirror): empty deltas for a static volume, the threshold's error
// bound, late joiners holding what everyone holds, deactivation, old / gap / other-scene frames,
// and the visibility data (distance moments, relocation offsets, probe states) end to end.
#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "net/probe_mirror.h"
#include "net/published_probes.h"
#include "sh/packing.h"
#include "net_test_util.h"

namespace ddish::net {
namespace {

constexpr std::uint64_t kScene = 77;

probes::ProbeVolume make_volume(std::mt19937_64& rng) {
  probes::ProbeVolume v(probes::ProbeGrid(scene::Aabb{glm::vec3(0.0f), glm::vec3(4.0f)}, {4, 4, 4}), 2);
  for (std::uint32_t i = 0; i < v.probe_count(); ++i) {
    v.set_sh(i, test::radiance_probe(rng, 2, 1.0f));
    v.state(i).flags = 0;
    v.state(i).updates = 1;
  }
  return v;
}

probes::ProbeVolume client_volume() {
  return probes::ProbeVolume(probes::ProbeGrid(scene::Aabb{glm::vec3(0.0f), glm::vec3(4.0f)}, {4, 4, 4}), 2);
}

DecodeResult decode_ok(const std::vector<std::uint8_t>& m) {
  DecodeResult r = decode_frame(m);
  EXPECT_TRUE(r.ok) << r.detail;
  return r;
}

TEST(Stream, StaticVolumeSendsOnceThenHeadersOnly) {
  std::mt19937_64 rng(1);
  probes::ProbeVolume server = make_volume(rng);
  PublishedProbes pub(server, kScene, 1, {.encoding = Encoding::kCompact, .threshold = 0.01f});
  PublishStats s;
  const auto first = pub.publish(server, 1, 100, 0.0, &s);
  EXPECT_EQ(s.sent, 64u);
  EXPECT_EQ(first.size(), kFrameHeaderBytes + 64 + 64 * 28);  // 1-byte gaps
  for (std::uint64_t frame = 2; frame < 10; ++frame) {
    const auto next = pub.publish(server, frame, 100 + std::int64_t(frame), 0.0, &s);
    EXPECT_EQ(s.sent, 0u);
    EXPECT_EQ(next.size(), kFrameHeaderBytes);
  }
  EXPECT_EQ(pub.held_probes(), 64u);
}

// A client that follows every delta stays within threshold × L0 + the encoding's error of the
// server's probes, while the server sends fewer probes than change.
TEST(Stream, ThresholdBoundsTheClientError) {
  std::mt19937_64 rng(2);
  probes::ProbeVolume server = make_volume(rng);
  probes::ProbeVolume client = client_volume();
  ProbeMirror mirror(client, kScene);
  const float threshold = 0.02f;
  PublishedProbes pub(server, kScene, 1, {.encoding = Encoding::kHalf, .threshold = threshold});
  std::normal_distribution<float> noise(0.0f, 0.004f);
  std::uint64_t sent = 0, held_back = 0;
  std::vector<std::uint32_t> changed;
  ASSERT_EQ(mirror.apply(decode_ok(pub.snapshot()).frame, changed), ApplyOutcome::kApplied);
  for (std::uint64_t frame = 1; frame <= 60; ++frame) {
    for (std::uint32_t i = 0; i < server.probe_count(); ++i)  // a slow random walk
      for (glm::vec3& c : server.coefficients(i)) c += glm::vec3(noise(rng), noise(rng), noise(rng));
    PublishStats s;
    const DecodeResult r = decode_ok(pub.publish(server, frame, 0, 0.0, &s));
    sent += s.sent;
    held_back += s.held_back;
    ASSERT_EQ(mirror.apply(r.frame, changed), ApplyOutcome::kApplied);
    for (std::uint32_t i = 0; i < server.probe_count(); ++i) {
      const auto a = server.coefficients(i), b = client.coefficients(i);
      const float l0 = std::max({std::fabs(a[0].x), std::fabs(a[0].y), std::fabs(a[0].z)});
      for (std::size_t j = 0; j < a.size(); ++j)
        for (int c = 0; c < 3; ++c)  // threshold, plus fp16 rounding of what was sent
          ASSERT_LE(std::fabs(a[j][c] - b[j][c]),
                    threshold * l0 + (std::fabs(a[j][c]) + threshold * l0) * 0x1p-11f + 1e-7f);
    }
  }
  EXPECT_GT(held_back, 0u);
  EXPECT_LT(sent, 60u * 64u);
}

TEST(Stream, LateJoinerHoldsWhatEveryoneHolds) {
  std::mt19937_64 rng(3);
  probes::ProbeVolume server = make_volume(rng);
  probes::ProbeVolume early = client_volume(), late = client_volume();
  ProbeMirror early_mirror(early, kScene), late_mirror(late, kScene);
  PublishedProbes pub(server, kScene, 1, {.encoding = Encoding::kCompact, .zstd = true, .threshold = 0.01f});
  std::vector<std::uint32_t> changed;
  ASSERT_EQ(early_mirror.apply(decode_ok(pub.snapshot()).frame, changed), ApplyOutcome::kApplied);
  std::normal_distribution<float> noise(0.0f, 0.01f);
  for (std::uint64_t frame = 1; frame <= 20; ++frame) {
    for (std::uint32_t i = frame % 3; i < server.probe_count(); i += 3)
      for (glm::vec3& c : server.coefficients(i)) c += glm::vec3(noise(rng));
    ASSERT_EQ(early_mirror.apply(decode_ok(pub.publish(server, frame, 0, 0.0)).frame, changed),
              ApplyOutcome::kApplied);
  }
  const DecodeResult snap = decode_ok(pub.snapshot());
  EXPECT_EQ(snap.frame.header.kind, FrameKind::kKeyframe);
  EXPECT_EQ(snap.frame.header.frame, 20u);
  ASSERT_EQ(late_mirror.apply(snap.frame, changed), ApplyOutcome::kApplied);
  EXPECT_EQ(changed.size(), 64u);  // a keyframe sets every probe
  for (std::uint32_t i = 0; i < 64; ++i)
    for (std::size_t j = 0; j < 9; ++j) ASSERT_EQ(early.coefficients(i)[j], late.coefficients(i)[j]);
  // Both take the next delta.
  const DecodeResult next = decode_ok(pub.publish(server, 21, 0, 0.0));
  EXPECT_EQ(early_mirror.apply(next.frame, changed), ApplyOutcome::kApplied);
  EXPECT_EQ(late_mirror.apply(next.frame, changed), ApplyOutcome::kApplied);
}

TEST(Stream, InactiveProbesAreAnnouncedOnceAndNeverSent) {
  std::mt19937_64 rng(4);
  probes::ProbeVolume server = make_volume(rng);
  server.deactivate(5, true);
  server.state(9).updates = 0;  // active, never traced: nothing to say
  PublishedProbes pub(server, kScene, 1, {});
  probes::ProbeVolume client = client_volume();
  ProbeMirror mirror(client, kScene);
  std::vector<std::uint32_t> changed;
  ASSERT_EQ(mirror.apply(decode_ok(pub.snapshot()).frame, changed), ApplyOutcome::kApplied);
  DecodeResult r = decode_ok(pub.publish(server, 1, 0, 0.0));
  EXPECT_EQ(r.frame.updated.size(), 62u);
  // Never held, but inside geometry: announced once (a client assumes a probe never sent
  // inactive, not inside).
  ASSERT_EQ(r.frame.deactivated, std::vector<std::uint32_t>{5});
  ASSERT_EQ(mirror.apply(r.frame, changed), ApplyOutcome::kApplied);
  EXPECT_FALSE(client.state(5).active());
  server.deactivate(12, true);
  PublishStats s;
  r = decode_ok(pub.publish(server, 2, 0, 0.0, &s));
  EXPECT_EQ(s.sent, 0u);
  ASSERT_EQ(r.frame.deactivated, std::vector<std::uint32_t>{12});
  EXPECT_EQ(r.frame.deactivated_flags[0], kWireFlagInactive | kWireFlagInsideGeometry);
  ASSERT_EQ(mirror.apply(r.frame, changed), ApplyOutcome::kApplied);
  EXPECT_EQ(changed, std::vector<std::uint32_t>{12});
  EXPECT_FALSE(client.state(12).active());
  EXPECT_TRUE(client.state(12).inside_geometry());
  EXPECT_EQ(client.coefficients(12)[0], glm::vec3(0.0f));
  r = decode_ok(pub.publish(server, 3, 0, 0.0));
  EXPECT_TRUE(r.frame.deactivated.empty());
  const DecodeResult snap = decode_ok(pub.snapshot());
  EXPECT_EQ(snap.frame.updated.size(), 61u);  // 64 less 5, 9 and 12
  EXPECT_EQ(snap.frame.deactivated, (std::vector<std::uint32_t>{5, 12}));  // inside geometry
}

TEST(Mirror, OldGapAndOtherSceneFrames) {
  std::mt19937_64 rng(5);
  probes::ProbeVolume server = make_volume(rng);
  PublishedProbes pub(server, kScene, 1, {});
  probes::ProbeVolume client = client_volume();
  ProbeMirror mirror(client, kScene);
  std::vector<std::uint32_t> changed;
  const auto d1 = pub.publish(server, 1, 0, 0.0);
  EXPECT_EQ(mirror.apply(decode_ok(d1).frame, changed), ApplyOutcome::kGap);  // no snapshot yet
  ASSERT_EQ(mirror.apply(decode_ok(pub.snapshot()).frame, changed), ApplyOutcome::kApplied);
  EXPECT_EQ(mirror.frame(), 1u);
  EXPECT_EQ(mirror.apply(decode_ok(d1).frame, changed), ApplyOutcome::kOld);  // older than it
  pub.publish(server, 2, 0, 0.0);  // lost
  EXPECT_EQ(mirror.apply(decode_ok(pub.publish(server, 3, 0, 0.0)).frame, changed), ApplyOutcome::kGap);
  // Another scene, another grid.
  PublishedProbes other(server, kScene + 1, 1, {});
  EXPECT_EQ(mirror.apply(decode_ok(other.snapshot()).frame, changed), ApplyOutcome::kSceneMismatch);
  probes::ProbeVolume coarse(probes::ProbeGrid(scene::Aabb{glm::vec3(0.0f), glm::vec3(4.0f)}, {2, 4, 8}), 2);
  PublishedProbes regridded(coarse, kScene, 1, {});
  EXPECT_EQ(mirror.apply(decode_ok(regridded.snapshot()).frame, changed), ApplyOutcome::kSceneMismatch);
  EXPECT_EQ(mirror.frame(), 1u);
  // A restarted server (another stream): its delta is a gap, its keyframe is taken although
  // its frame number is lower.
  PublishedProbes restarted(server, kScene, 2, {});
  restarted.publish(server, 1, 0, 0.0);
  EXPECT_EQ(mirror.apply(decode_ok(restarted.publish(server, 2, 0, 0.0)).frame, changed), ApplyOutcome::kGap);
  EXPECT_EQ(mirror.apply(decode_ok(restarted.snapshot()).frame, changed), ApplyOutcome::kApplied);
  EXPECT_EQ(mirror.stream(), 2u);
  EXPECT_EQ(mirror.frame(), 2u);
}

TEST(Mirror, ARestartedServerLeavesTheHeldProbesUntilItSendsThem) {
  std::mt19937_64 rng(6);
  probes::ProbeVolume server = make_volume(rng);
  server.deactivate(7, true);
  PublishedProbes pub(server, kScene, 1, {});
  probes::ProbeVolume client = client_volume();
  ProbeMirror mirror(client, kScene);
  std::vector<std::uint32_t> changed;
  pub.publish(server, 1, 0, 0.0);
  ASSERT_EQ(mirror.apply(decode_ok(pub.snapshot()).frame, changed), ApplyOutcome::kApplied);
  EXPECT_EQ(mirror.kept(), 0u);
  const std::vector<glm::vec3> held(client.coefficients(3).begin(), client.coefficients(3).end());
  const std::vector<glm::vec3> held40(client.coefficients(40).begin(), client.coefficients(40).end());

  // The new server has traced probes 0..9 only (probe 7 is inside geometry for it too).
  probes::ProbeVolume fresh = client_volume();
  for (std::uint32_t i = 0; i < 10; ++i) {
    fresh.set_sh(i, test::radiance_probe(rng, 2, 2.0f));
    fresh.state(i).flags = 0;
    fresh.state(i).updates = 1;
  }
  fresh.deactivate(7, true);
  PublishedProbes restarted(server, kScene, 2, {});
  restarted.publish(fresh, 1, 0, 0.0);
  mirror.desync();  // the client noticed the loss
  ASSERT_EQ(mirror.apply(decode_ok(restarted.snapshot()).frame, changed), ApplyOutcome::kApplied);
  EXPECT_EQ(mirror.kept(), 64u - 10u);  // 10..63 kept: active, with what the old server sent
  EXPECT_EQ(changed.size(), 10u);
  EXPECT_FALSE(client.state(7).active());
  EXPECT_TRUE(client.state(40).active());
  for (std::size_t j = 0; j < 9; ++j) EXPECT_NE(client.coefficients(3)[j], held[j]);  // resent
  for (std::size_t j = 0; j < 9; ++j) EXPECT_EQ(client.coefficients(40)[j], held40[j]);  // kept
  EXPECT_NE(held40[0], glm::vec3(0.0f));

  // A keyframe of the same stream (a re-snapshot after a lost delta) is the whole truth.
  mirror.desync();
  restarted.publish(fresh, 2, 0, 0.0);
  ASSERT_EQ(mirror.apply(decode_ok(restarted.snapshot()).frame, changed), ApplyOutcome::kApplied);
  EXPECT_EQ(mirror.kept(), 0u);
  EXPECT_FALSE(client.state(40).active());
}

// A volume with 4x4 moment maps, a few relocated probes and inactive ones (inside geometry, and
// left out), as a server with --probe-visibility 4 --probe-relocation holds it.
probes::ProbeVolume visibility_volume(std::mt19937_64& rng) {
  probes::ProbeVolume v(probes::ProbeGrid(scene::Aabb{glm::vec3(0.0f), glm::vec3(4.0f)}, {4, 4, 4}), 2, 4);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (std::uint32_t i = 0; i < v.probe_count(); ++i) {
    v.set_sh(i, test::radiance_probe(rng, 2, 1.0f));
    v.state(i).flags = 0;
    v.state(i).updates = 1;
    for (glm::vec2& m : v.moments(i)) {
      const float d = u(rng);
      m = glm::vec2(d, d * d);
    }
  }
  v.set_offset(5, glm::vec3(0.45f, -0.3f, 0.01f));  // at the bound on x: 0.45 of a 1 m cell
  v.set_offset(40, glm::vec3(-0.2f, 0.0f, 0.45f));
  v.deactivate(9, true);    // inside geometry
  v.deactivate(33, false);  // left out (no surface near it)
  return v;
}

// Moves a texel's mean distance by d and keeps its spread (the variance m2 - m1^2).
void move_mean(glm::vec2& m, float d) {
  m.y += (m.x + d) * (m.x + d) - m.x * m.x;
  m.x += d;
}

void expect_same_visibility(const probes::ProbeVolume& client, const probes::ProbeVolume& server) {
  for (std::uint32_t i = 0; i < server.probe_count(); ++i) {
    EXPECT_EQ(client.state(i).active(), server.state(i).active()) << i;
    EXPECT_EQ(client.state(i).inside_geometry(), server.state(i).inside_geometry()) << i;
    EXPECT_EQ(client.offset(i), server.offset(i)) << i;  // exact: f32 on the wire
    for (std::size_t t = 0; t < server.moments(i).size(); ++t)
      for (int c = 0; c < 2; ++c)  // the halves the rasterizer would upload from either
        EXPECT_EQ(sh::float_to_half(client.moments(i)[t][c]), sh::float_to_half(server.moments(i)[t][c]))
            << i << " " << t;
  }
}

TEST(Stream, MomentsOffsetsAndStatesReachEveryClient) {
  std::mt19937_64 rng(8);
  probes::ProbeVolume server = visibility_volume(rng);
  for (glm::vec2& m : server.moments(17)) m = glm::vec2(0.4f, 0.4f * 0.4f + 0.01f);  // room to move
  PublishedProbes pub(server, kScene, 1, {.encoding = Encoding::kCompact, .threshold = 0.01f, .moment_threshold = 0.01f});
  probes::ProbeVolume client(server.grid(), 2, 4);
  ProbeMirror mirror(client, kScene);
  std::vector<std::uint32_t> changed;
  pub.publish(server, 1, 0, 0.0);
  ASSERT_EQ(mirror.apply(decode_ok(pub.snapshot()).frame, changed), ApplyOutcome::kApplied);
  expect_same_visibility(client, server);
  // A map that moves by more than the threshold re-sends its probe, and only it; a probe that
  // leaves geometry after a reset and is relocated afresh, too.
  for (glm::vec2& m : server.moments(17)) move_mean(m, -0.05f);  // 0.05 / sqrt(2) = 0.035
  const std::vector<glm::vec2> map18(server.moments(18).begin(), server.moments(18).end());
  move_mean(server.moments(18)[3], -0.02f);  // 0.02 / sqrt(32) = 0.0035 of the range: held back
  server.set_offset(40, glm::vec3(0.1f, 0.1f, 0.1f));
  server.deactivate(12, true);
  PublishStats stats;
  const auto delta = pub.publish(server, 2, 0, 0.0, &stats);
  EXPECT_EQ(stats.sent, 2u);
  EXPECT_EQ(stats.maps, 2u);  // 17's moved, 40 relocated
  EXPECT_EQ(stats.held_back, 1u);
  EXPECT_EQ(stats.deactivated, 1u);
  ASSERT_EQ(mirror.apply(decode_ok(delta).frame, changed), ApplyOutcome::kApplied);
  EXPECT_EQ(changed, (std::vector<std::uint32_t>{12, 17, 40}));
  std::copy(map18.begin(), map18.end(), server.moments(18).begin());  // what the client holds for 18
  expect_same_visibility(client, server);
  // A late joiner's snapshot carries the same.
  probes::ProbeVolume late(server.grid(), 2, 4);
  ProbeMirror late_mirror(late, kScene);
  ASSERT_EQ(late_mirror.apply(decode_ok(pub.snapshot()).frame, changed), ApplyOutcome::kApplied);
  expect_same_visibility(late, server);
  // Bytes: 2 + 1 + 1 + 2 index bytes, a flag, compact L2 coefficients of 28 bytes and 4x4 maps
  // of 4 x 16 = 64 per probe, an offset of 12.
  EXPECT_EQ(delta.size(), kFrameHeaderBytes + 2 + 1 + 1 + 2 + 1 + 2 * (28 + 64) + 12);
}

void expect_same_probes(const probes::ProbeVolume& a, const probes::ProbeVolume& b) {
  for (std::uint32_t i = 0; i < a.probe_count(); ++i) {
    EXPECT_EQ(a.state(i).active(), b.state(i).active()) << i;
    for (std::size_t j = 0; j < a.coefficients(i).size(); ++j) EXPECT_EQ(a.coefficients(i)[j], b.coefficients(i)[j]) << i;
    for (std::size_t t = 0; t < a.moments(i).size(); ++t) EXPECT_EQ(a.moments(i)[t], b.moments(i)[t]) << i << " " << t;
    EXPECT_EQ(a.offset(i), b.offset(i)) << i;
  }
}

// moment_map_change: the root mean square over the texels of the change of the mean distance
// and of the spread, each a fraction of the range.
TEST(Stream, MomentMapChangeIsTheRmsOfMeanAndSpread) {
  const auto map = [](float mean, float spread) {
    return std::vector<glm::vec2>(16, glm::vec2(mean, mean * mean + spread * spread));
  };
  const std::vector<glm::vec2> a = map(0.5f, 0.1f);
  EXPECT_EQ(moment_map_change(a, a), 0.0f);
  EXPECT_NEAR(moment_map_change(a, map(0.54f, 0.1f)), 0.04f / std::sqrt(2.0f), 1e-5f);  // every mean
  EXPECT_NEAR(moment_map_change(a, map(0.5f, 0.13f)), 0.03f / std::sqrt(2.0f), 1e-5f);  // every spread
  std::vector<glm::vec2> one = a;
  move_mean(one[7], 0.08f);
  EXPECT_NEAR(moment_map_change(a, one), 0.08f / std::sqrt(32.0f), 1e-5f);  // one texel of 16
  EXPECT_NEAR(moment_map_change(one, a), moment_map_change(a, one), 1e-7f);
  EXPECT_THROW(moment_map_change(a, std::vector<glm::vec2>(8, a[0])), std::invalid_argument);
}

// A probe re-sent for its coefficients alone carries no moment map, and the client keeps the
// map it holds; a map that moved beyond the moment threshold (moment_map_change) since the one
// last sent travels (with its probe's coefficients, whether they moved or not), as does the map
// of a probe back from inactive; a late joiner's keyframe holds every map everyone holds.
TEST(Stream, MomentMapsTravelOnlyWhenTheyMove) {
  std::mt19937_64 rng(10);
  probes::ProbeVolume server = visibility_volume(rng);
  for (std::uint32_t i : {20u, 21u, 22u})  // moments with room to move within [0, 1]
    for (glm::vec2& m : server.moments(i)) m = glm::vec2(0.4f, 0.4f * 0.4f + 0.01f);
  PublishedProbes pub(server, kScene, 1,
                      {.encoding = Encoding::kCompact, .threshold = 0.01f, .moment_threshold = 0.01f});
  probes::ProbeVolume client(server.grid(), 2, 4);
  ProbeMirror mirror(client, kScene);
  std::vector<std::uint32_t> changed;
  PublishStats stats;
  pub.publish(server, 1, 0, 0.0, &stats);
  EXPECT_EQ(stats.maps, stats.sent);  // first sent: every probe with its map
  ASSERT_EQ(mirror.apply(decode_ok(pub.snapshot()).frame, changed), ApplyOutcome::kApplied);
  const std::vector<glm::vec2> map20(client.moments(20).begin(), client.moments(20).end());
  server.set_sh(20, test::radiance_probe(rng, 2, 1.0f));  // coefficients far beyond 1 %
  // One texel's mean 0.05 of the range away is 0.05 / sqrt(2 x 16) = 0.0088 of the map: within
  // the threshold, not sent (one texel of a map gets about one path an update: noise).
  move_mean(server.moments(20)[5], 0.05f);
  for (glm::vec2& m : server.moments(21)) move_mean(m, 0.02f);  // 0.02 / sqrt(2) = 0.014: sent
  const auto delta = pub.publish(server, 2, 0, 0.0, &stats);
  EXPECT_EQ(stats.sent, 2u);
  EXPECT_EQ(stats.maps, 1u);
  const DecodeResult r = decode_ok(delta);
  EXPECT_EQ(r.frame.updated, (std::vector<std::uint32_t>{20, 21}));
  EXPECT_EQ(r.frame.mapped, (std::vector<std::uint32_t>{21}));
  EXPECT_EQ(delta.size(), kFrameHeaderBytes + 2 + 1 + 2 * 28 + 64);  // 2 + 1 index bytes
  ASSERT_EQ(mirror.apply(r.frame, changed), ApplyOutcome::kApplied);
  EXPECT_EQ(changed, (std::vector<std::uint32_t>{20, 21}));
  for (std::size_t t = 0; t < map20.size(); ++t) EXPECT_EQ(client.moments(20)[t], map20[t]) << t;  // kept
  for (std::size_t t = 0; t < 16; ++t) EXPECT_NEAR(client.moments(21)[t].y, server.moments(21)[t].y, 0x1p-11f) << t;
  EXPECT_NEAR(client.coefficients(20)[0].x, server.coefficients(20)[0].x, 1e-2f * server.coefficients(20)[0].x);
  // The threshold counts from the map last sent, not the last tick's: 0.005 more on the same
  // texel is 0.055 / sqrt(32) = 0.0097, within; 0.005 again, 0.060 / sqrt(32) = 0.0106, sent.
  for (std::uint64_t frame = 3; frame <= 4; ++frame) {
    move_mean(server.moments(20)[5], 0.005f);
    const DecodeResult drift = decode_ok(pub.publish(server, frame, 0, 0.0, &stats));
    EXPECT_EQ(stats.maps, frame == 4 ? 1u : 0u) << frame;
    ASSERT_EQ(mirror.apply(drift.frame, changed), ApplyOutcome::kApplied);
  }
  EXPECT_NEAR(client.moments(20)[5].x, server.moments(20)[5].x, 0x1p-11f);
  // Back from inactive with the very map it had: sent whole (the client reset it).
  const std::vector<glm::vec2> map30(server.moments(30).begin(), server.moments(30).end());
  server.deactivate(30, false);
  ASSERT_EQ(mirror.apply(decode_ok(pub.publish(server, 6, 0, 0.0)).frame, changed), ApplyOutcome::kApplied);
  server.state(30).flags = 0;
  server.state(30).updates = 1;
  std::copy(map30.begin(), map30.end(), server.moments(30).begin());
  const DecodeResult back = decode_ok(pub.publish(server, 7, 0, 0.0, &stats));
  EXPECT_EQ(back.frame.mapped, (std::vector<std::uint32_t>{30}));
  ASSERT_EQ(mirror.apply(back.frame, changed), ApplyOutcome::kApplied);
  for (std::size_t t = 0; t < map30.size(); ++t)
    EXPECT_EQ(sh::float_to_half(client.moments(30)[t].x), sh::float_to_half(map30[t].x)) << t;
  // A map held back leaves the client within the threshold of the server's; a late joiner holds
  // exactly what the client that followed every delta holds, not the server's newer map.
  move_mean(server.moments(22)[0], 0.04f);
  const DecodeResult held = decode_ok(pub.publish(server, 8, 0, 0.0, &stats));
  EXPECT_EQ(stats.held_back, 1u);
  ASSERT_EQ(mirror.apply(held.frame, changed), ApplyOutcome::kApplied);
  for (std::uint32_t i = 0; i < server.probe_count(); ++i) {
    if (!server.state(i).active()) continue;
    EXPECT_LE(moment_map_change(client.moments(i), server.moments(i)), 0.01f + 0x1p-11f) << i;
  }
  probes::ProbeVolume late(server.grid(), 2, 4);
  ProbeMirror late_mirror(late, kScene);
  const DecodeResult snap = decode_ok(pub.snapshot());
  EXPECT_EQ(snap.frame.mapped, snap.frame.updated);
  ASSERT_EQ(late_mirror.apply(snap.frame, changed), ApplyOutcome::kApplied);
  expect_same_probes(late, client);
}

TEST(Mirror, RefusesAnotherMomentMapAndOffsetsBeyondTheCell) {
  std::mt19937_64 rng(9);
  probes::ProbeVolume server = visibility_volume(rng);
  PublishedProbes pub(server, kScene, 1, {});
  pub.publish(server, 1, 0, 0.0);
  std::vector<std::uint32_t> changed;
  for (int resolution : {0, 8}) {  // a client sized for no moments, or for other maps
    probes::ProbeVolume other(server.grid(), 2, resolution);
    ProbeMirror mirror(other, kScene);
    EXPECT_EQ(mirror.apply(decode_ok(pub.snapshot()).frame, changed), ApplyOutcome::kSceneMismatch);
  }
  // Offsets: 0.45 of the 1 m cell on an axis is the bound; a hostile server's 0.46 is refused
  // before anything of its frame is applied.
  probes::ProbeVolume client(server.grid(), 2, 4);
  ProbeMirror mirror(client, kScene);
  DecodeResult r = decode_ok(pub.snapshot());
  r.frame.offsets[0].x = 0.46f;
  EXPECT_EQ(mirror.apply(r.frame, changed), ApplyOutcome::kBadOffset);
  EXPECT_FALSE(mirror.synced());
  EXPECT_EQ(client.offset(5), glm::vec3(0.0f));
  r.frame.offsets[0].x = -0.45f;
  EXPECT_EQ(mirror.apply(r.frame, changed), ApplyOutcome::kApplied);
  EXPECT_EQ(client.offset(5).x, -0.45f);
}

}  // namespace
}  // namespace ddish::net
