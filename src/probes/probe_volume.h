// A probe volume: the grid layout plus, for every probe, its SH coefficients (the fp32 running
// average of the radiance arriving at the probe, RGB, orders L1..L4) and the state the probe
// tracer and the scheduler need (updates and samples received, age, active / inside-geometry).
// Optionally, per-probe distance moments (moment_map.h) blended with the same weights as the SH,
// for visibility-aware interpolation; a volume without them (moment resolution 0) is
// interpolated trilinearly, as before they existed.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "probes/accumulation.h"
#include "probes/moment_map.h"
#include "probes/probe_grid.h"
#include "sh/sh_rgb.h"

namespace ddish::probes {

inline constexpr int kDefaultShOrder = 2;
// A relocated probe stays within this fraction of a cell of its grid position on every axis
// (DDGI's 0.45): it never leaves its cell, so the interpolation's cell structure holds.
inline constexpr float kMaxRelocation = 0.45f;

// Per-probe flags (a bit set, stored as one byte in volume files).
enum ProbeFlag : std::uint8_t {
  kProbeInactive = 1u << 0,        // not traced; interpolation gives it zero weight
  kProbeInsideGeometry = 1u << 1,  // why it is inactive: classification found it inside geometry
  kProbeUnclassified = 1u << 2,    // its next update classifies it (set on new probes)
};

struct ProbeState {
  std::uint32_t updates = 0;  // updates blended into the running average
  std::uint64_t samples = 0;  // paths (rays from the probe) those updates traced
  std::uint32_t age = 0;      // volume updates since this probe was last updated
  float backface_fraction = 0.0f;  // of the rays of its last classification
  std::uint8_t flags = kProbeUnclassified;

  bool active() const { return (flags & kProbeInactive) == 0; }
  bool inside_geometry() const { return (flags & kProbeInsideGeometry) != 0; }
  bool unclassified() const { return (flags & kProbeUnclassified) != 0; }
};

// Throws std::invalid_argument unless 1 <= order <= 4.
void check_sh_order(int order);

class ProbeVolume {
 public:
  ProbeVolume() : ProbeVolume(ProbeGrid(), kDefaultShOrder) {}  // one probe at the origin
  // moment_resolution: R of the R x R distance-moment map per probe, 0 for none
  // (std::invalid_argument outside 0..kMaxMomentResolution).
  ProbeVolume(const ProbeGrid& grid, int sh_order = kDefaultShOrder, int moment_resolution = 0);

  const ProbeGrid& grid() const { return grid_; }
  int sh_order() const { return order_; }
  // SH coefficients per colour channel: (order + 1)^2 (sh::coeff_count).
  int coefficient_count() const { return coeff_count_; }
  std::uint32_t probe_count() const { return grid_.probe_count(); }

  // The running average of probe i: coefficient_count() RGB coefficients, coefficient j of
  // channel c at [j][c].
  std::span<glm::vec3> coefficients(std::uint32_t i) {
    return {coeffs_.data() + std::size_t(i) * std::size_t(coeff_count_), std::size_t(coeff_count_)};
  }
  std::span<const glm::vec3> coefficients(std::uint32_t i) const {
    return {coeffs_.data() + std::size_t(i) * std::size_t(coeff_count_), std::size_t(coeff_count_)};
  }
  // All probes' coefficients, probe after probe in grid index order.
  std::span<const glm::vec3> all_coefficients() const { return coeffs_; }

  // Distance moments: moment_texels() texels per probe, (mean d, mean d^2) / (range, range^2)
  // (moment_map.h). A texel no ray has reached yet holds (1, 1): nothing within the range.
  int moment_resolution() const { return moment_res_; }
  bool has_moments() const { return moment_res_ > 0; }
  int moment_texels() const { return moment_res_ * moment_res_; }
  // Distances are clamped to this and stored divided by it: 1.5 cell diagonals (an interpolated
  // point is at most one diagonal from each probe it reads, plus the shader's bias).
  float moment_range() const { return moment_range_; }
  std::span<glm::vec2> moments(std::uint32_t i) {
    return {moments_.data() + std::size_t(i) * std::size_t(moment_texels()), std::size_t(moment_texels())};
  }
  std::span<const glm::vec2> moments(std::uint32_t i) const {
    return {moments_.data() + std::size_t(i) * std::size_t(moment_texels()), std::size_t(moment_texels())};
  }

  // Relocation: probe i's offset from its grid position (zero unless relocated), and where it
  // traces from. set_offset clamps each axis to kMaxRelocation cells.
  const glm::vec3& offset(std::uint32_t i) const { return offsets_[i]; }
  void set_offset(std::uint32_t i, const glm::vec3& offset);
  glm::vec3 position(std::uint32_t i) const { return grid_.position(i) + offsets_[i]; }

  const ProbeState& state(std::uint32_t i) const { return states_[i]; }
  ProbeState& state(std::uint32_t i) { return states_[i]; }

  // Probe i's running average as SH coefficients of the volume's order.
  sh::ShRgb sh(std::uint32_t i) const;
  void set_sh(std::uint32_t i, const sh::ShRgb& coefficients);  // bands above the order dropped

  // Blends a new estimate into probe i's running average with the weight of its next update
  // (accumulation.h) and counts the update and its samples. Bands above the order are ignored.
  // rule and reference_samples choose the weight (accumulation.h); reference_samples 0 means
  // `samples` (the per-sample rule then equals the per-update rule at full samples).
  // With `moments` (of the volume's moment resolution), each texel that rays reached blends
  // their mean with the same weight; texels no ray reached keep their value.
  void accumulate(std::uint32_t i, const sh::ShRgb& estimate, std::uint64_t samples,
                  float hysteresis, BlendRule rule = BlendRule::per_update,
                  std::uint32_t reference_samples = 0, const MomentEstimate* moments = nullptr);

  // Marks probe i inactive (inside geometry or not), zeroes its coefficients and counts and
  // resets its moments, so
  // an interpolation that ignored the flag would still add nothing.
  void deactivate(std::uint32_t i, bool inside_geometry);

  // Re-runs classification at the next update of every probe (after the geometry changed, say):
  // active probes keep their average until then; inactive ones become active again with a zero
  // average, so a probe that is no longer inside anything starts accumulating.
  void reset_classification();

  // Volume-wide update counter: begin_update() starts update number frame() + 1 and ages
  // every probe by one; the probe tracer resets the age of the probes it updates.
  void begin_update();
  std::uint64_t frame() const { return frame_; }
  // Restores the counter of a volume read from a file, so later updates draw fresh samples.
  void set_frame(std::uint64_t frame) { frame_ = frame; }

  std::uint32_t active_count() const;
  std::uint32_t inactive_count() const { return probe_count() - active_count(); }
  std::uint32_t inside_geometry_count() const;

 private:
  ProbeGrid grid_;
  int order_ = kDefaultShOrder;
  int coeff_count_ = sh::coeff_count(kDefaultShOrder);
  std::vector<glm::vec3> coeffs_;
  std::vector<ProbeState> states_;
  int moment_res_ = 0;
  float moment_range_ = 1.0f;
  std::vector<glm::vec2> moments_;
  std::vector<glm::vec3> offsets_;
  std::uint64_t frame_ = 0;
};

}  // namespace ddish::probes
