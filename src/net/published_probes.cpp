#include "net/published_probes.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ddish::net {

PublishedProbes::PublishedProbes(const probes::ProbeGrid& grid, int sh_order, std::uint64_t scene_id,
                                 std::uint64_t stream_id, const StreamOptions& options,
                                 std::vector<std::uint32_t> probes)
    : options_(options),
      coefficient_count_((sh_order + 1) * (sh_order + 1)),
      probe_bytes_(std::size_t(probe_bytes(options.encoding, sh_order))) {
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
  held_bytes_.assign(probes_.size() * probe_bytes_, 0);
  source_.assign(probes_.size() * std::size_t(coefficient_count_), glm::vec3(0.0f));
  grid_probes_ = grid.probe_count();
}

std::uint32_t PublishedProbes::held_probes() const {
  return std::uint32_t(std::count(held_.begin(), held_.end(), std::uint8_t(1)));
}

std::vector<std::uint8_t> PublishedProbes::publish(const probes::ProbeVolume& volume,
                                                   std::uint64_t frame, std::int64_t server_time_us,
                                                   double scene_time, PublishStats* stats) {
  if (volume.probe_count() != grid_probes_ || volume.sh_order() != header_.sh_order)
    throw std::invalid_argument("PublishedProbes::publish: another grid or SH order");
  if (frame <= header_.frame)
    throw std::invalid_argument("PublishedProbes::publish: frames must increase");
  PublishStats s;
  std::vector<std::uint32_t> updated, deactivated;
  std::vector<std::uint8_t> flags, bytes;
  const std::size_t n = std::size_t(coefficient_count_);
  for (std::size_t k = 0; k < probes_.size(); ++k) {
    const std::uint32_t i = probes_[k];
    const probes::ProbeState& state = volume.state(i);
    if (!state.active()) {
      if (held_[k]) {
        held_[k] = 0;
        deactivated.push_back(i);
        flags.push_back(std::uint8_t(kWireFlagInactive |
                                     (state.inside_geometry() ? kWireFlagInsideGeometry : 0)));
      }
      continue;
    }
    if (state.updates == 0) continue;  // nothing to say yet: it stays out of the interpolation
    std::span<const glm::vec3> now = volume.coefficients(i);
    glm::vec3* src = source_.data() + k * n;
    if (held_[k]) {
      float change = 0.0f;
      for (std::size_t j = 0; j < n; ++j) {
        const glm::vec3 d = glm::abs(now[j] - src[j]);
        change = std::max({change, d.x, d.y, d.z});
      }
      const float l0 = std::max({std::fabs(now[0].x), std::fabs(now[0].y), std::fabs(now[0].z)});
      const float allowed = std::max(options_.threshold * l0, options_.floor);
      if (change <= allowed) {
        if (change > 0.0f) ++s.held_back;
        continue;
      }
    }
    std::uint8_t* out = held_bytes_.data() + k * probe_bytes_;
    if (!encode_probe(header_.encoding, header_.sh_order, now, std::span(out, probe_bytes_)))
      ++s.saturated;
    std::copy(now.begin(), now.end(), src);
    held_[k] = 1;
    updated.push_back(i);
    bytes.insert(bytes.end(), out, out + probe_bytes_);
  }
  FrameHeader h = header_;
  h.kind = FrameKind::kDelta;
  h.base_frame = header_.frame;
  h.frame = frame;
  h.server_time_us = server_time_us;
  h.scene_time = scene_time;
  std::vector<std::uint8_t> message =
      encode_frame(h, updated, bytes, deactivated, flags, options_.zstd_level);
  header_.frame = frame;
  header_.server_time_us = server_time_us;
  header_.scene_time = scene_time;
  s.sent = std::uint32_t(updated.size());
  s.deactivated = std::uint32_t(deactivated.size());
  s.bytes = message.size();
  if (stats) *stats = s;
  return message;
}

std::vector<std::uint8_t> PublishedProbes::snapshot() const {
  std::vector<std::uint32_t> updated;
  std::vector<std::uint8_t> bytes;
  for (std::size_t k = 0; k < held_.size(); ++k) {
    if (!held_[k]) continue;
    updated.push_back(probes_[k]);
    const std::uint8_t* b = held_bytes_.data() + k * probe_bytes_;
    bytes.insert(bytes.end(), b, b + probe_bytes_);
  }
  FrameHeader h = header_;
  h.kind = FrameKind::kKeyframe;
  h.base_frame = h.frame;
  return encode_frame(h, updated, bytes, {}, {}, options_.zstd_level);
}

}  // namespace ddish::net
