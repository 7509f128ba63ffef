#include "probes/probe_volume.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "probes/accumulation.h"

namespace ddish::probes {

void check_sh_order(int order) {
  if (order < 1 || order > 4)
    throw std::invalid_argument("SH order must be 1, 2, 3 or 4, got " + std::to_string(order));
}

namespace {
float moment_range_of(const ProbeGrid& grid) {
  float diagonal = glm::length(grid.spacing());
  // One probe, or a grid flat on every axis: the bounds' size stands in for the cell's.
  if (!(diagonal > 0.0f)) diagonal = glm::length(grid.bounds().max - grid.bounds().min);
  return diagonal > 0.0f && std::isfinite(diagonal) ? 1.5f * diagonal : 1.0f;
}
}  // namespace

ProbeVolume::ProbeVolume(const ProbeGrid& grid, int sh_order, int moment_resolution)
    : grid_(grid), order_(sh_order), coeff_count_(sh::coeff_count(sh_order)),
      moment_res_(moment_resolution), moment_range_(moment_range_of(grid)) {
  check_sh_order(sh_order);
  check_moment_resolution(moment_resolution);
  coeffs_.assign(std::size_t(grid.probe_count()) * std::size_t(coeff_count_), glm::vec3(0.0f));
  states_.assign(grid.probe_count(), ProbeState{});
  moments_.assign(std::size_t(grid.probe_count()) * std::size_t(moment_texels()), glm::vec2(1.0f));
  offsets_.assign(grid.probe_count(), glm::vec3(0.0f));
}

void ProbeVolume::set_offset(std::uint32_t i, const glm::vec3& offset) {
  const glm::vec3 bound = kMaxRelocation * grid_.spacing();
  glm::vec3 o = glm::clamp(offset, -bound, bound);
  for (int a = 0; a < 3; ++a)
    if (!std::isfinite(o[a])) o[a] = 0.0f;
  offsets_[i] = o;
}

sh::ShRgb ProbeVolume::sh(std::uint32_t i) const {
  sh::ShRgb out(order_);
  std::span<const glm::vec3> avg = coefficients(i);
  std::copy(avg.begin(), avg.end(), out.c.begin());
  return out;
}

void ProbeVolume::set_sh(std::uint32_t i, const sh::ShRgb& coefficients_in) {
  std::span<glm::vec3> avg = coefficients(i);
  for (std::size_t j = 0; j < avg.size(); ++j)
    avg[j] = int(j) < coefficients_in.count() ? coefficients_in.c[j] : glm::vec3(0.0f);
}

void ProbeVolume::accumulate(std::uint32_t i, const sh::ShRgb& estimate, std::uint64_t samples,
                             float hysteresis, BlendRule rule, std::uint32_t reference_samples,
                             const MomentEstimate* moments) {
  ProbeState& s = states_[i];
  // The weight depends on the history before this update: its updates, samples and how many
  // volume updates passed since the probe was last blended (begin_update aged it already).
  const BlendHistory history{s.updates, s.samples, std::max<std::uint32_t>(s.age, 1u)};
  const float w = blend_weight(rule, history, samples, hysteresis,
                               reference_samples ? reference_samples : std::uint32_t(samples));
  s.updates += 1;
  s.samples += samples;
  s.age = 0;
  std::span<glm::vec3> avg = coefficients(i);
  for (std::size_t j = 0; j < avg.size(); ++j) {
    const glm::vec3 e = int(j) < estimate.count() ? estimate.c[j] : glm::vec3(0.0f);
    // w == 1 on the first update: assign, so the zero start leaves no trace at all.
    avg[j] = w == 1.0f ? e : avg[j] + w * (e - avg[j]);
  }
  if (moments && has_moments()) {
    if (moments->resolution != moment_res_)
      throw std::invalid_argument("moment estimate of resolution " +
                                  std::to_string(moments->resolution) + " for a volume of " +
                                  std::to_string(moment_res_));
    std::span<glm::vec2> m = this->moments(i);
    for (std::size_t t = 0; t < m.size(); ++t) {
      if (moments->count[t] == 0) continue;
      const glm::vec2 e = moments->sum[t] / float(moments->count[t]);
      m[t] = w == 1.0f ? e : m[t] + w * (e - m[t]);
    }
  }
}

void ProbeVolume::deactivate(std::uint32_t i, bool inside_geometry) {
  ProbeState& s = states_[i];
  s.flags = std::uint8_t(inside_geometry ? kProbeInactive | kProbeInsideGeometry : kProbeInactive);
  s.updates = 0;
  s.samples = 0;
  std::span<glm::vec3> avg = coefficients(i);
  std::fill(avg.begin(), avg.end(), glm::vec3(0.0f));
  std::span<glm::vec2> m = moments(i);
  std::fill(m.begin(), m.end(), glm::vec2(1.0f));
}

void ProbeVolume::reset_classification() {
  for (ProbeState& s : states_) {
    if (s.active()) {
      s.flags = std::uint8_t(s.flags | kProbeUnclassified);  // keeps its average
    } else {
      const std::uint32_t age = s.age;
      s = ProbeState{};  // a fresh probe: zero average (deactivate zeroed it), unclassified
      s.age = age;
      offsets_[std::size_t(&s - states_.data())] = glm::vec3(0.0f);  // relocated afresh
    }
  }
}

void ProbeVolume::begin_update() {
  ++frame_;
  for (ProbeState& s : states_) ++s.age;
}

std::uint32_t ProbeVolume::active_count() const {
  return std::uint32_t(std::count_if(states_.begin(), states_.end(),
                                     [](const ProbeState& s) { return s.active(); }));
}

std::uint32_t ProbeVolume::inside_geometry_count() const {
  return std::uint32_t(std::count_if(states_.begin(), states_.end(),
                                     [](const ProbeState& s) { return s.inside_geometry(); }));
}

}  // namespace ddish::probes
