#include "net/published_probes.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ddish::net {

float moment_map_change(std::span<const glm::vec2> a, std::span<const glm::vec2> b) {
  if (a.size() != b.size()) throw std::invalid_argument("moment_map_change: maps of different sizes");
  if (a.empty()) return 0.0f;
  // The Chebyshev weight of a texel reads the mean and the variance; the spread is the variance
  // in the mean's units, so the two changes add as lengths. One texel's change is noise (about
  // one path a texel and update at 8x8 and 64 paths): the aggregate over the map is what moves
  // the weights of a whole face of the cell.
  const auto spread = [](const glm::vec2& m) { return std::sqrt(std::max(m.y - m.x * m.x, 0.0f)); };
  double sum = 0.0;
  for (std::size_t t = 0; t < a.size(); ++t) {
    const double dm = double(a[t].x) - double(b[t].x);
    const double ds = double(spread(a[t])) - double(spread(b[t]));
    sum += dm * dm + ds * ds;
  }
  return float(std::sqrt(sum / double(2 * a.size())));
}

PublishedProbes::PublishedProbes(const probes::ProbeVolume& volume, std::uint64_t scene_id,
                                 std::uint64_t stream_id, const StreamOptions& options,
                                 std::vector<std::uint32_t> probes)
    : options_(options),
      coefficient_count_(volume.coefficient_count()),
      sh_bytes_(std::size_t(probe_bytes(options.encoding, volume.sh_order()))),
      map_bytes_(moment_bytes(volume.moment_texels())),
      texels_(std::size_t(volume.moment_texels())) {
  const probes::ProbeGrid& grid = volume.grid();
  const int sh_order = volume.sh_order();
  header_.moment_resolution = volume.moment_resolution();
  header_.moment_range = volume.has_moments() ? volume.moment_range() : 0.0f;
  header_.kind = FrameKind::kKeyframe;
  header_.encoding = options.encoding;
  header_.sh_order = sh_order;
  header_.zstd = options.zstd;
  header_.counts[0] = std::uint32_t(grid.counts().x);
  header_.counts[1] = std::uint32_t(grid.counts().y);
  header_.counts[2] = std::uint32_t(grid.counts().z);
  header_.scene_id = scene_id;
  header_.stream_id = stream_id;
  if (probes.empty())
    for (std::uint32_t i = 0; i < grid.probe_count(); ++i) probes.push_back(i);
  for (std::size_t k = 0; k < probes.size(); ++k)
    if (probes[k] >= grid.probe_count() || (k > 0 && probes[k] <= probes[k - 1]))
      throw std::invalid_argument("PublishedProbes: probes must be increasing grid indices");
  probes_ = std::move(probes);
  held_.assign(probes_.size(), 0);
  held_coefficients_.assign(probes_.size() * sh_bytes_, 0);
  held_maps_.assign(probes_.size() * map_bytes_, 0);
  source_.assign(probes_.size() * std::size_t(coefficient_count_), glm::vec3(0.0f));
  source_moments_.assign(probes_.size() * texels_, glm::vec2(0.0f));
  held_offsets_.assign(probes_.size(), glm::vec3(0.0f));
  announced_.assign(probes_.size(), kWireFlagInactive);
  announced_offsets_.assign(probes_.size(), glm::vec3(0.0f));
  grid_probes_ = grid.probe_count();
}

std::uint32_t PublishedProbes::held_probes() const {
  return std::uint32_t(std::count(held_.begin(), held_.end(), std::uint8_t(1)));
}

std::vector<std::uint8_t> PublishedProbes::publish(const probes::ProbeVolume& volume,
                                                   std::uint64_t frame, std::int64_t server_time_us,
                                                   double scene_time, PublishStats* stats) {
  if (volume.probe_count() != grid_probes_ || volume.sh_order() != header_.sh_order ||
      volume.moment_resolution() != header_.moment_resolution)
    throw std::invalid_argument("PublishedProbes::publish: another grid, SH order or moment resolution");
  if (frame <= header_.frame)
    throw std::invalid_argument("PublishedProbes::publish: frames must increase");
  PublishStats s;
  std::vector<std::uint32_t> updated, mapped, deactivated, relocated;
  std::vector<std::uint8_t> flags, coefficients, maps;
  std::vector<glm::vec3> offsets;
  const std::size_t n = std::size_t(coefficient_count_);
  for (std::size_t k = 0; k < probes_.size(); ++k) {
    const std::uint32_t i = probes_[k];
    const probes::ProbeState& state = volume.state(i);
    if (!state.active()) {
      const std::uint8_t wire = std::uint8_t(kWireFlagInactive |
                                             (state.inside_geometry() ? kWireFlagInsideGeometry : 0));
      // Announced once: a probe subscribers held, or whose state is not what they assume of a
      // probe never sent (inactive, not inside geometry: left out, say).
      const glm::vec3& offset = volume.offset(i);
      if (held_[k] || announced_[k] != wire || announced_offsets_[k] != offset) {
        held_[k] = 0;
        announced_[k] = wire;
        announced_offsets_[k] = offset;
        deactivated.push_back(i);
        flags.push_back(wire);
        if (offset != glm::vec3(0.0f)) {
          relocated.push_back(i);
          offsets.push_back(offset);
        }
      }
      continue;
    }
    if (state.updates == 0) continue;  // nothing to say yet: it stays out of the interpolation
    std::span<const glm::vec3> now = volume.coefficients(i);
    std::span<const glm::vec2> moments_now = volume.moments(i);
    const glm::vec3& offset = volume.offset(i);
    glm::vec3* src = source_.data() + k * n;
    glm::vec2* src_moments = source_moments_.data() + k * texels_;
    // A probe held at the same offset goes again when its coefficients moved beyond the bound,
    // with its map only when that moved beyond the threshold since the map last sent; any
    // other (first sent, back from inactive, relocated) goes whole.
    bool send_coefficients = true, send_map = texels_ > 0;
    if (held_[k] && offset == held_offsets_[k]) {
      float change = 0.0f;
      for (std::size_t j = 0; j < n; ++j) {
        const glm::vec3 d = glm::abs(now[j] - src[j]);
        change = std::max({change, d.x, d.y, d.z});
      }
      const float moment_change =
          texels_ > 0 ? moment_map_change(moments_now, std::span<const glm::vec2>(src_moments, texels_)) : 0.0f;
      const float l0 = std::max({std::fabs(now[0].x), std::fabs(now[0].y), std::fabs(now[0].z)});
      const float allowed = std::max(options_.threshold * l0, options_.floor);
      send_map = moment_change > options_.moment_threshold;
      send_coefficients = send_map || change > allowed;
      if (!send_coefficients) {
        if (change > 0.0f || moment_change > 0.0f) ++s.held_back;
        continue;
      }
    }
    std::uint8_t* out = held_coefficients_.data() + k * sh_bytes_;
    bool exact = encode_probe(header_.encoding, header_.sh_order, now, std::span(out, sh_bytes_));
    std::copy(now.begin(), now.end(), src);
    updated.push_back(i);
    coefficients.insert(coefficients.end(), out, out + sh_bytes_);
    if (send_map) {
      std::uint8_t* map = held_maps_.data() + k * map_bytes_;
      exact &= encode_moments(moments_now, std::span(map, map_bytes_));
      std::copy(moments_now.begin(), moments_now.end(), src_moments);
      mapped.push_back(i);
      maps.insert(maps.end(), map, map + map_bytes_);
    }
    if (!exact) ++s.saturated;
    held_offsets_[k] = offset;
    held_[k] = 1;
    announced_[k] = kWireFlagInactive;  // what an unlisted probe is, should it go again
    announced_offsets_[k] = glm::vec3(0.0f);
    if (offset != glm::vec3(0.0f)) {
      relocated.push_back(i);
      offsets.push_back(offset);
    }
  }
  FrameHeader h = header_;
  h.kind = FrameKind::kDelta;
  h.base_frame = header_.frame;
  h.frame = frame;
  h.server_time_us = server_time_us;
  h.scene_time = scene_time;
  std::vector<std::uint8_t> message = encode_frame(
      h, FrameParts{updated, coefficients, mapped, maps, deactivated, flags, relocated, offsets},
      options_.zstd_level);
  header_.frame = frame;
  header_.server_time_us = server_time_us;
  header_.scene_time = scene_time;
  s.sent = std::uint32_t(updated.size());
  s.maps = std::uint32_t(mapped.size());
  s.deactivated = std::uint32_t(deactivated.size());
  s.bytes = message.size();
  if (stats) *stats = s;
  return message;
}

std::vector<std::uint8_t> PublishedProbes::description() const {
  FrameHeader h = header_;
  h.kind = FrameKind::kKeyframe;
  h.base_frame = h.frame;
  h.zstd = false;
  return encode_frame(h, FrameParts{});
}

std::vector<std::uint8_t> PublishedProbes::snapshot() const {
  std::vector<std::uint32_t> updated, mapped, relocated, deactivated;
  std::vector<std::uint8_t> coefficients, maps, flags;
  std::vector<glm::vec3> offsets;
  for (std::size_t k = 0; k < held_.size(); ++k) {
    if (!held_[k]) {
      if (announced_[k] != kWireFlagInactive || announced_offsets_[k] != glm::vec3(0.0f)) {
        deactivated.push_back(probes_[k]);  // inside geometry, or relocated before it was found so
        flags.push_back(announced_[k]);
        if (announced_offsets_[k] != glm::vec3(0.0f)) {
          relocated.push_back(probes_[k]);
          offsets.push_back(announced_offsets_[k]);
        }
      }
      continue;
    }
    // Every held probe with the map subscribers hold of it: a keyframe leaves nothing to an
    // earlier frame.
    updated.push_back(probes_[k]);
    const std::uint8_t* c = held_coefficients_.data() + k * sh_bytes_;
    coefficients.insert(coefficients.end(), c, c + sh_bytes_);
    if (map_bytes_ > 0) {
      mapped.push_back(probes_[k]);
      const std::uint8_t* m = held_maps_.data() + k * map_bytes_;
      maps.insert(maps.end(), m, m + map_bytes_);
    }
    if (held_offsets_[k] != glm::vec3(0.0f)) {
      relocated.push_back(probes_[k]);
      offsets.push_back(held_offsets_[k]);
    }
  }
  FrameHeader h = header_;
  h.kind = FrameKind::kKeyframe;
  h.base_frame = h.frame;
  return encode_frame(h, FrameParts{updated, coefficients, mapped, maps, deactivated, flags, relocated, offsets},
                      options_.zstd_level);
}

}  // namespace ddish::net
