#include "net/probe_mirror.h"

#include <algorithm>

#include <glm/glm.hpp>

namespace ddish::net {
namespace {

// `moments`: the probe's map, or null when the frame does not carry it (the probe keeps its own).
void set_probe(probes::ProbeVolume& volume, std::uint32_t i, const glm::vec3* coefficients,
               const glm::vec2* moments, const glm::vec3& offset) {
  std::span<glm::vec3> dst = volume.coefficients(i);
  std::copy(coefficients, coefficients + dst.size(), dst.begin());
  if (moments) {
    std::span<glm::vec2> m = volume.moments(i);
    std::copy(moments, moments + m.size(), m.begin());
  }
  volume.set_offset(i, offset);
  probes::ProbeState& s = volume.state(i);
  s.flags = 0;  // active and classified: the server traced it
  s.updates = std::max(s.updates, 1u);
  s.age = 0;
}

void deactivate_probe(probes::ProbeVolume& volume, std::uint32_t i, bool inside_geometry,
                      const glm::vec3& offset) {
  volume.deactivate(i, inside_geometry);
  volume.set_offset(i, offset);
}

// The offset of each probe of `list` (zero unless relocated).
std::vector<glm::vec3> offsets_of(const std::vector<std::uint32_t>& list, const ProbeFrame& f) {
  std::vector<glm::vec3> out(list.size(), glm::vec3(0.0f));
  for (std::size_t a = 0, b = 0; a < list.size() && b < f.relocated.size(); ++a) {
    while (b < f.relocated.size() && f.relocated[b] < list[a]) ++b;
    if (b < f.relocated.size() && f.relocated[b] == list[a]) out[a] = f.offsets[b];
  }
  return out;
}

// Per probe of `f.updated`, its moment map in the frame, or null when it has none there.
std::vector<const glm::vec2*> maps_of(const ProbeFrame& f, std::size_t texels) {
  std::vector<const glm::vec2*> out(f.updated.size(), nullptr);
  for (std::size_t a = 0, b = 0; a < f.updated.size() && b < f.mapped.size(); ++a) {
    while (b < f.mapped.size() && f.mapped[b] < f.updated[a]) ++b;
    if (b < f.mapped.size() && f.mapped[b] == f.updated[a]) out[a] = f.moments.data() + b * texels;
  }
  return out;
}

}  // namespace

ProbeMirror::ProbeMirror(probes::ProbeVolume& volume, std::uint64_t scene_id,
                         std::vector<std::uint32_t> probes)
    : volume_(volume), scene_id_(scene_id), probes_(std::move(probes)) {
  if (probes_.empty())
    for (std::uint32_t i = 0; i < volume_.probe_count(); ++i) probes_.push_back(i);
  mine_.assign(volume_.probe_count(), 0);
  for (std::uint32_t i : probes_)
    if (i < mine_.size()) mine_[i] = 1;
}

bool ProbeMirror::matches(const FrameHeader& h) const {
  const glm::ivec3 c = volume_.grid().counts();
  if (h.moment_resolution != volume_.moment_resolution() ||
      (h.moment_resolution > 0 && h.moment_range != volume_.moment_range()))
    return false;
  return h.scene_id == scene_id_ && h.sh_order == volume_.sh_order() &&
         h.counts[0] == std::uint32_t(c.x) && h.counts[1] == std::uint32_t(c.y) &&
         h.counts[2] == std::uint32_t(c.z);
}

ApplyOutcome ProbeMirror::apply(const ProbeFrame& f, std::vector<std::uint32_t>& changed) {
  changed.clear();
  if (!matches(f.header)) return ApplyOutcome::kSceneMismatch;
  const std::size_t n = std::size_t(volume_.coefficient_count());
  for (const std::vector<std::uint32_t>* list : {&f.updated, &f.deactivated})
    for (std::uint32_t i : *list)
      if (i >= mine_.size() || !mine_[i]) return ApplyOutcome::kOutside;
  // The same bound set_offset clamps to (the grid is the server's: the scene identity covers it).
  const glm::vec3 bound = probes::kMaxRelocation * volume_.grid().spacing();
  for (const glm::vec3& o : f.offsets)
    if (glm::any(glm::greaterThan(glm::abs(o), bound))) return ApplyOutcome::kBadOffset;
  const std::vector<glm::vec3> offsets = offsets_of(f.updated, f);
  const std::vector<glm::vec3> deactivated_offsets = offsets_of(f.deactivated, f);
  const std::vector<const glm::vec2*> maps = maps_of(f, std::size_t(volume_.moment_texels()));
  if (f.header.kind == FrameKind::kKeyframe) {
    kept_ = 0;
    if (synced_ && f.header.stream_id == stream_ && f.header.frame <= frame_) return ApplyOutcome::kOld;
    // A restarted server of the same scene and grid has not traced most probes yet: the probes
    // the client holds stay until the new stream sends them (each probe's first update is
    // always sent), rather than the indirect light going dark after every restart.
    const bool restarted = stream_ != 0 && f.header.stream_id != stream_;
    std::size_t next = 0, next_off = 0;
    for (std::uint32_t i : probes_) {
      if (next < f.updated.size() && f.updated[next] == i) {
        set_probe(volume_, i, f.coefficients.data() + next * n, maps[next], offsets[next]);
        ++next;
      } else if (next_off < f.deactivated.size() && f.deactivated[next_off] == i) {
        deactivate_probe(volume_, i, (f.deactivated_flags[next_off] & kWireFlagInsideGeometry) != 0,
                         deactivated_offsets[next_off]);
        ++next_off;
      } else if (restarted && volume_.state(i).active() && volume_.state(i).updates > 0) {
        ++kept_;
        continue;
      } else {
        deactivate_probe(volume_, i, false, glm::vec3(0.0f));
      }
      changed.push_back(i);
    }
  } else {
    if (!synced_ || f.header.stream_id != stream_) return ApplyOutcome::kGap;
    if (f.header.frame <= frame_) return ApplyOutcome::kOld;
    if (f.header.base_frame != frame_) return ApplyOutcome::kGap;
    for (std::size_t k = 0; k < f.updated.size(); ++k)
      set_probe(volume_, f.updated[k], f.coefficients.data() + k * n, maps[k], offsets[k]);
    for (std::size_t k = 0; k < f.deactivated.size(); ++k)
      deactivate_probe(volume_, f.deactivated[k], (f.deactivated_flags[k] & kWireFlagInsideGeometry) != 0,
                       deactivated_offsets[k]);
    std::merge(f.updated.begin(), f.updated.end(), f.deactivated.begin(), f.deactivated.end(),
               std::back_inserter(changed));
  }
  synced_ = true;
  frame_ = f.header.frame;
  stream_ = f.header.stream_id;
  return ApplyOutcome::kApplied;
}

}  // namespace ddish::net
