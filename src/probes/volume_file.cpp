#include "probes/volume_file.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/atomic_file.h"
#include "sh/packing.h"

namespace ddish::probes {

// Fields are copied as they are in memory, and the packer's words are in host order: the
// format is little-endian, so the host must be too (every platform ddish targets is).
static_assert(std::endian::native == std::endian::little, "volume files assume a little-endian host");

namespace {

template <typename T>
void put(std::vector<std::uint8_t>& buf, std::size_t offset, T value) {
  std::memcpy(buf.data() + offset, &value, sizeof(T));
}

template <typename T>
T get(const std::vector<std::uint8_t>& buf, std::size_t offset) {
  T value;
  std::memcpy(&value, buf.data() + offset, sizeof(T));
  return value;
}

[[noreturn]] void fail(const std::string& path, const std::string& problem) {
  throw std::runtime_error(path + ": " + problem);
}

nlohmann::json summary(const ProbeVolume& volume, const PackedVolume& packed) {
  const ProbeGrid& g = volume.grid();
  std::uint64_t samples = 0;
  std::uint32_t max_updates = 0;
  for (std::uint32_t i = 0; i < volume.probe_count(); ++i) {
    samples += volume.state(i).samples;
    max_updates = std::max(max_updates, volume.state(i).updates);
  }
  nlohmann::json j;
  j["format"] = "DDPV";
  j["version"] = kVolumeVersion;
  j["counts"] = {g.counts().x, g.counts().y, g.counts().z};
  j["bounds"] = {{"min", {g.bounds().min.x, g.bounds().min.y, g.bounds().min.z}},
                 {"max", {g.bounds().max.x, g.bounds().max.y, g.bounds().max.z}}};
  j["spacing"] = {g.spacing().x, g.spacing().y, g.spacing().z};
  j["placement"] = "cell centres (inset half a cell from the bounds)";
  j["probes"] = volume.probe_count();
  j["active"] = volume.active_count();
  j["inactive"] = volume.inactive_count();
  j["inside_geometry"] = volume.inside_geometry_count();
  j["sh_order"] = volume.sh_order();
  j["moment_resolution"] = volume.moment_resolution();
  j["encoding"] = encoding_name(packed.encoding);
  j["fp16_probes"] = packed.half_probes;
  j["shared_exponent_probes"] = packed.shared_exp_probes;
  j["saturated_probes"] = packed.overflowed_probes;
  j["bytes_per_probe"] = packed.words_per_probe * 2u;
  j["updates"] = volume.frame();
  j["max_probe_updates"] = max_updates;
  j["samples"] = samples;
  return j;
}

}  // namespace

void write_volume_file(const std::string& path, const ProbeVolume& volume,
                       const PackedVolume& packed) {
  if (packed.sh_order != volume.sh_order() || packed.probe_count() != volume.probe_count() ||
      packed.words_per_probe != std::uint32_t(sh::packed_words(volume.sh_order())))
    throw std::invalid_argument("write_volume_file: the packed volume does not match the volume");
  const ProbeGrid& g = volume.grid();
  std::vector<std::uint8_t> header(kVolumeHeaderBytes, 0);
  std::memcpy(header.data(), kVolumeMagic, 4);
  put(header, 4, kVolumeVersion);
  for (int a = 0; a < 3; ++a) {
    put(header, 8 + 4 * std::size_t(a), std::int32_t(g.counts()[a]));
    put(header, 20 + 4 * std::size_t(a), g.bounds().min[a]);
    put(header, 32 + 4 * std::size_t(a), g.bounds().max[a]);
  }
  put(header, 44, std::uint32_t(volume.sh_order()));
  put(header, 48, std::uint32_t(packed.encoding));
  put(header, 52, packed.words_per_probe);
  put(header, 56, std::uint64_t(volume.frame()));

  // Both files whole or not at all (io/atomic_file.h); the volume first, so a summary never
  // describes a volume that is not there.
  std::string bytes(header.begin(), header.end());
  bytes.append(reinterpret_cast<const char*>(packed.words.data()), packed.bytes());
  std::vector<std::uint32_t> moments(1, std::uint32_t(volume.moment_resolution()));
  for (std::uint32_t i = 0; i < volume.probe_count(); ++i)
    for (const glm::vec2& m : volume.moments(i))
      moments.push_back(std::uint32_t(sh::float_to_half(m.x)) |
                        (std::uint32_t(sh::float_to_half(m.y)) << 16));
  bytes.append(reinterpret_cast<const char*>(moments.data()), moments.size() * 4);
  std::vector<float> offsets;
  for (std::uint32_t i = 0; i < volume.probe_count(); ++i)
    for (int a = 0; a < 3; ++a) offsets.push_back(volume.offset(i)[a]);
  bytes.append(reinterpret_cast<const char*>(offsets.data()), offsets.size() * 4);
  io::write_file_atomically(path, bytes);
  io::write_file_atomically(path + ".json", summary(volume, packed).dump(2) + '\n');
}

VolumeFile read_volume_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open");
  std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                  std::istreambuf_iterator<char>());
  if (bytes.size() < kVolumeHeaderBytes || std::memcmp(bytes.data(), kVolumeMagic, 4) != 0)
    fail(path, "not a ddish probe volume (no DDPV header)");
  const auto version = get<std::uint32_t>(bytes, 4);
  if (version != 1 && version != kVolumeVersion)
    fail(path, "probe volume version " + std::to_string(version) + " is not supported (1 or " +
                   std::to_string(kVolumeVersion) + ")");
  glm::ivec3 counts;
  scene::Aabb bounds;
  for (int a = 0; a < 3; ++a) {
    counts[a] = get<std::int32_t>(bytes, 8 + 4 * std::size_t(a));
    bounds.min[a] = get<float>(bytes, 20 + 4 * std::size_t(a));
    bounds.max[a] = get<float>(bytes, 32 + 4 * std::size_t(a));
  }
  const auto order = get<std::uint32_t>(bytes, 44);
  const auto encoding = get<std::uint32_t>(bytes, 48);
  const auto words = get<std::uint32_t>(bytes, 52);

  VolumeFile file;
  try {
    file.grid = ProbeGrid(bounds, counts);
    check_sh_order(int(order));
  } catch (const std::invalid_argument& e) {
    fail(path, e.what());
  }
  if (encoding > std::uint32_t(Encoding::kMixed))
    fail(path, "unknown encoding " + std::to_string(encoding));
  if (words != std::uint32_t(sh::packed_words(int(order))))
    fail(path, "words per probe " + std::to_string(words) + " does not match SH order " +
                   std::to_string(order));
  const std::size_t payload = std::size_t(file.grid.probe_count()) * words * 2u;
  std::size_t expected = kVolumeHeaderBytes + payload;
  if (version >= 2) {
    if (bytes.size() < expected + 4)
      fail(path, "size " + std::to_string(bytes.size()) + " bytes, expected at least " +
                     std::to_string(expected + 4) + " (truncated or corrupt)");
    const auto res = get<std::uint32_t>(bytes, expected);
    if (res > std::uint32_t(kMaxMomentResolution))
      fail(path, "moment map resolution " + std::to_string(res) + " (at most " +
                     std::to_string(kMaxMomentResolution) + ")");
    file.moment_resolution = int(res);
    expected += 4 + std::size_t(file.grid.probe_count()) * (res * res * 4u + 12u);
  }
  if (bytes.size() != expected)
    fail(path, "size " + std::to_string(bytes.size()) + " bytes, expected " +
                   std::to_string(expected) + " (truncated or corrupt)");

  file.frame = get<std::uint64_t>(bytes, 56);
  PackedVolume& p = file.packed;
  p.sh_order = int(order);
  p.words_per_probe = words;
  p.encoding = Encoding(encoding);
  p.words.resize(payload / 2);
  std::memcpy(p.words.data(), bytes.data() + kVolumeHeaderBytes, payload);
  if (file.moment_resolution > 0) {
    file.moments.resize(std::size_t(file.grid.probe_count()) *
                        std::size_t(file.moment_resolution * file.moment_resolution));
    std::memcpy(file.moments.data(), bytes.data() + kVolumeHeaderBytes + payload + 4,
                file.moments.size() * 4);
  }
  if (version >= 2) {
    file.offsets.resize(std::size_t(file.grid.probe_count()) * 3);
    std::memcpy(file.offsets.data(), bytes.data() + kVolumeHeaderBytes + payload + 4 + file.moments.size() * 4,
                file.offsets.size() * 4);
  }
  for (std::uint32_t i = 0; i < file.grid.probe_count(); ++i)
    (sh::packed_format(p.probe(i), p.sh_order) == sh::PackFormat::kHalf ? p.half_probes
                                                                        : p.shared_exp_probes) += 1;
  return file;
}

ProbeVolume VolumeFile::to_volume() const {
  ProbeVolume volume(grid, packed.sh_order, moment_resolution);
  volume.set_frame(frame);
  const std::size_t texels = std::size_t(volume.moment_texels());
  for (std::uint32_t i = 0; i < grid.probe_count(); ++i) {
    volume.set_sh(i, unpack_probe(packed, i));
    volume.state(i).flags = unpack_flags(packed, i);
    if (!offsets.empty())  // untrusted: set_offset clamps to the cell and zeroes NaN
      volume.set_offset(i, {offsets[3 * i], offsets[3 * i + 1], offsets[3 * i + 2]});
    std::span<glm::vec2> m = volume.moments(i);
    for (std::size_t t = 0; t < texels; ++t) {
      const std::uint32_t v = moments[i * texels + t];
      // Untrusted halves: NaN or out-of-range values become "nothing in the way".
      glm::vec2 d(sh::half_to_float(std::uint16_t(v & 0xffffu)), sh::half_to_float(std::uint16_t(v >> 16)));
      if (!(d.x >= 0.0f && d.x <= 1.0f && d.y >= 0.0f && d.y <= 1.0f)) d = glm::vec2(1.0f);
      m[t] = d;
    }
  }
  return volume;
}

}  // namespace ddish::probes
