// Packing a volume (fp16, shared exponent where fp16 would overflow) and volume files.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "probes/probe_tracer.h"
#include "probes/volume_file.h"
#include "probes/volume_packing.h"
#include "synthetic_sources.h"

using namespace ddish::probes;
using ddish::probes::synthetic::FunctionSource;
using ddish::scene::Aabb;
using ddish::sh::PackFormat;
using ddish::sh::PackStatus;
using ddish::trace::Ray;
using ddish::trace::Sampler;
namespace synthetic = ddish::probes::synthetic;

namespace {

// Probes in a dim room (radiance ~1 around them) and, for probes with x > 0, a 1e6-radiance
// emitter filling the quarter of the sphere towards +x (solid angle π): their L0 coefficient
// is about 1e6 · π · 0.282 = 8.9e5, far above fp16's 65504.
FunctionSource emitter_source() {
  return FunctionSource([](const Ray& r, Sampler&) {
    bool lit = r.origin.x > 0.0f && r.direction.x > 0.5f;
    return synthetic::uniform(lit ? glm::vec3(1e6f, 5e5f, 2e5f)
                                  : glm::vec3(0.2f, 0.5f, 1.0f) * (1.0f + r.direction.y));
  });
}

ProbeVolume traced_volume(const ddish::probes::RadianceSource& source, int order = 2) {
  ProbeVolume volume(ProbeGrid(Aabb{{-1.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f}}, {2, 2, 1}), order);
  ProbeTracer(source, UpdateOptions{.samples = 128, .seed = 3}).update(volume);
  return volume;
}

std::string temp_path(const std::string& name) {
  return (std::filesystem::path(::testing::TempDir()) / name).string();
}

}  // namespace

TEST(VolumePacking, DimVolumeIsFp16At56BytesPerL2Probe) {
  FunctionSource source([](const Ray& r, Sampler&) {
    return synthetic::uniform(glm::vec3(0.3f, 1.0f, 3.0f) * (1.5f + r.direction.z));
  });
  ProbeVolume volume = traced_volume(source);
  PackedVolume packed = pack_volume(volume);
  EXPECT_EQ(packed.encoding, Encoding::kHalf);
  EXPECT_EQ(packed.status, PackStatus::kOk);
  EXPECT_EQ(packed.words_per_probe * 2u, 56u);
  EXPECT_EQ(packed.bytes(), 4u * 56u);
  for (std::uint32_t i = 0; i < volume.probe_count(); ++i) {
    ddish::sh::ShRgb a = volume.sh(i), b = unpack_probe(packed, i);
    for (int j = 0; j < a.count(); ++j)
      for (int ch = 0; ch < 3; ++ch)  // fp16: 11 significant bits, rounding error <= 2^-11
        EXPECT_NEAR(b[j][ch], a[j][ch], std::abs(a[j][ch]) * 0x1p-11f + 1e-7f);
  }
}

TEST(VolumePacking, BrightEmitterSwitchesToSharedExponentNeverInf) {
  FunctionSource source = emitter_source();
  ProbeVolume volume = traced_volume(source);
  std::uint32_t bright = 0;
  for (std::uint32_t i = 0; i < volume.probe_count(); ++i) {
    ddish::sh::ShRgb c = volume.sh(i);
    bool near_emitter = volume.grid().position(i).x > 0.0f;
    if (!near_emitter) continue;
    ++bright;
    ASSERT_GT(c[0].x, 5e5f);  // about 8.9e5
    // fp16 packing of this probe reports the overflow instead of writing Inf.
    std::uint16_t words[ddish::sh::packed_words(2)];
    EXPECT_EQ(ddish::sh::pack_half(c, 0, words), PackStatus::kOverflow);
  }
  ASSERT_EQ(bright, 2u);

  PackedVolume packed = pack_volume(volume);
  EXPECT_EQ(packed.status, PackStatus::kOk);
  EXPECT_EQ(packed.encoding, Encoding::kMixed);
  EXPECT_EQ(packed.shared_exp_probes, 2u);
  EXPECT_EQ(packed.half_probes, 2u);
  EXPECT_EQ(packed.overflowed_probes, 0u);
  for (std::uint32_t i = 0; i < volume.probe_count(); ++i) {
    bool near_emitter = volume.grid().position(i).x > 0.0f;
    EXPECT_EQ(ddish::sh::packed_format(packed.probe(i), 2),
              near_emitter ? PackFormat::kSharedExp : PackFormat::kHalf);
    ddish::sh::ShRgb a = volume.sh(i), b = unpack_probe(packed, i);
    for (int ch = 0; ch < 3; ++ch) {
      float channel_max = 0.0f;
      for (int j = 0; j < a.count(); ++j) channel_max = std::max(channel_max, std::abs(a[j][ch]));
      for (int j = 0; j < a.count(); ++j) {
        ASSERT_TRUE(std::isfinite(b[j][ch]));
        // The shared-exponent form's stated bound: error <= max |channel| / 16383.
        float tol = near_emitter ? channel_max / 16383.0f
                                 : std::abs(a[j][ch]) * 0x1p-11f + 1e-7f;
        EXPECT_NEAR(b[j][ch], a[j][ch], tol) << "probe " << i << " coefficient " << j;
      }
    }
  }

  // Forcing fp16 on the whole volume saturates and says so; still no Inf.
  PackedVolume forced = pack_volume(volume, EncodingPolicy::kHalf);
  EXPECT_EQ(forced.status, PackStatus::kOverflow);
  EXPECT_EQ(forced.overflowed_probes, 2u);
  for (std::uint32_t i = 0; i < volume.probe_count(); ++i) {
    const ddish::sh::ShRgb saturated = unpack_probe(forced, i);
    for (const glm::vec3& v : saturated.coeffs())
      ASSERT_TRUE(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z));
  }

  PackedVolume all_shared = pack_volume(volume, EncodingPolicy::kSharedExp);
  EXPECT_EQ(all_shared.encoding, Encoding::kSharedExp);
  EXPECT_EQ(all_shared.shared_exp_probes, 4u);
}

TEST(VolumeFile, RoundTrip) {
  FunctionSource source = emitter_source();
  ProbeVolume volume = traced_volume(source, 3);
  volume.deactivate(1, true);  // a flagged probe must survive the trip
  PackedVolume packed = pack_volume(volume);
  const std::string path = temp_path("probes_round_trip.ddpv");
  write_volume_file(path, volume, packed);

  // Version 2: the probes, then a zero moment resolution (no moments), then the offsets.
  EXPECT_EQ(std::filesystem::file_size(path),
            kVolumeHeaderBytes + 4u * packed.words_per_probe * 2u + 4u + 4u * 12u);
  VolumeFile file = read_volume_file(path);
  EXPECT_EQ(file.grid, volume.grid());
  EXPECT_EQ(file.frame, 1u);
  EXPECT_EQ(file.packed.sh_order, 3);
  EXPECT_EQ(file.packed.encoding, Encoding::kMixed);
  EXPECT_EQ(file.packed.words, packed.words);
  EXPECT_EQ(file.packed.shared_exp_probes, packed.shared_exp_probes);

  ProbeVolume back = file.to_volume();
  EXPECT_EQ(back.frame(), 1u);
  EXPECT_EQ(back.inactive_count(), 1u);
  EXPECT_TRUE(back.state(1).inside_geometry());
  EXPECT_FALSE(back.state(1).active());
  for (std::uint32_t i = 0; i < volume.probe_count(); ++i) {
    EXPECT_EQ(back.state(i).active(), volume.state(i).active());
    ddish::sh::ShRgb expect = unpack_probe(packed, i), got = back.sh(i);
    for (int j = 0; j < expect.count(); ++j) EXPECT_EQ(got[j], expect[j]);
  }

  std::ifstream js(path + ".json");
  nlohmann::json summary = nlohmann::json::parse(js);
  EXPECT_EQ(summary["format"], "DDPV");
  EXPECT_EQ(summary["probes"], 4);
  EXPECT_EQ(summary["inactive"], 1);
  EXPECT_EQ(summary["encoding"], "mixed");
  EXPECT_EQ(summary["bytes_per_probe"], 2 * (3 * 16 + 1));
}

TEST(VolumeFile, MomentsSurviveTheTripAndVersionOneFilesStillRead) {
  ProbeVolume volume(ProbeGrid(ddish::scene::Aabb{{-1.0f, -1.0f, -1.0f}, {1.0f, 1.0f, 1.0f}}, {2, 1, 1}), 2, 3);
  for (std::uint32_t i = 0; i < 2; ++i)
    for (int t = 0; t < 9; ++t) volume.moments(i)[std::size_t(t)] = {0.125f * float(t + i), 0.0625f * float(t)};
  volume.set_offset(1, {0.25f, -0.125f, 0.0f});
  const std::string path = temp_path("probes_moments.ddpv");
  PackedVolume packed = pack_volume(volume);
  write_volume_file(path, volume, packed);
  EXPECT_EQ(std::filesystem::file_size(path), kVolumeHeaderBytes + packed.bytes() + 4u + 2u * (9u * 4u + 12u));
  ProbeVolume back = read_volume_file(path).to_volume();
  ASSERT_EQ(back.moment_resolution(), 3);
  EXPECT_EQ(back.offset(0), glm::vec3(0.0f));
  EXPECT_EQ(back.offset(1), glm::vec3(0.25f, -0.125f, 0.0f));
  for (std::uint32_t i = 0; i < 2; ++i)
    for (int t = 0; t < 9; ++t) {
      const glm::vec2 want = volume.moments(i)[std::size_t(t)];
      EXPECT_EQ(back.moments(i)[std::size_t(t)], t + i > 8 ? glm::vec2(1.0f) : want)  // > 1: refused
          << "probe " << i << " texel " << t;
    }

  // The same file as version 1 wrote it: no moment section. It reads, without moments.
  {
    std::string bytes;
    {
      std::ifstream in(path, std::ios::binary);
      bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    bytes.resize(kVolumeHeaderBytes + packed.bytes());
    bytes[4] = 1;
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << bytes;
  }
  ProbeVolume v1 = read_volume_file(path).to_volume();
  EXPECT_FALSE(v1.has_moments());
  EXPECT_EQ(v1.probe_count(), 2u);
  // A version 1 header with a moment section is the wrong size: refused.
  {
    std::ofstream out(path, std::ios::binary | std::ios::app);
    out << std::string(4, '\0');
  }
  EXPECT_THROW(read_volume_file(path), std::runtime_error);
}

TEST(VolumeFile, RejectsBrokenFiles) {
  FunctionSource source = emitter_source();
  ProbeVolume volume = traced_volume(source);
  const std::string path = temp_path("probes_broken.ddpv");
  write_volume_file(path, volume, pack_volume(volume));
  std::filesystem::resize_file(path, std::filesystem::file_size(path) - 2);
  EXPECT_THROW(read_volume_file(path), std::runtime_error);
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << "not a volume at all, just some text that is long enough for a header .........";
  }
  EXPECT_THROW(read_volume_file(path), std::runtime_error);
  EXPECT_THROW(read_volume_file(temp_path("no_such_volume.ddpv")), std::runtime_error);
}
