// The probe update: for every active probe, N paths from the probe position in the directions of
// a randomly rotated spherical Fibonacci lattice, their radiance projected onto SH (weight 4π/N
// per path) and blended into the probe's fp32 running average. A probe's first update also
// classifies it (classification.h). When the volume keeps distance moments (moment_map.h), the
// same rays' first-hit distances feed them: no extra rays. Parallel over probes with TBB; every probe draws from its own
// Sampler stream (seed, probe index, volume update number), so the coefficients depend on the
// seed and the sequence of updates only, never on how threads split the work.
#pragma once

#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "probes/accumulation.h"
#include "probes/classification.h"
#include "probes/probe_updater.h"
#include "probes/probe_volume.h"
#include "sh/sh_rgb.h"
#include "trace/tracer.h"  // Ray, PathSample

namespace ddish::probes {

// Where probe rays get their radiance: the path tracer in ddish, anything else in tests.
class RadianceSource {
 public:
  virtual ~RadianceSource() = default;
  // Radiance arriving at ray.origin from ray.direction, with its first-hit facts. Called
  // concurrently from several threads.
  virtual trace::PathSample trace_path(const trace::Ray& ray, trace::Sampler& sampler) const = 0;
  // Rays cast so far (for Mrays/s); sources that cast none report the paths asked for.
  virtual std::uint64_t rays_traced() const = 0;
};

struct UpdateOptions {
  std::uint32_t samples = 256;         // paths per probe per update (--probe-samples)
  float hysteresis = kDefaultHysteresis;
  std::uint64_t seed = 0;
  float backface_threshold = kInsideBackfaceFraction;
  BlendRule blend = BlendRule::per_update;  // how an update is weighed into the average
  std::uint32_t reference_samples = 0;      // S of the per-sample rule; 0: samples
  // Relocation at classification: a probe found inside geometry moves through the nearest back
  // face it saw, one nearer than kMinSurfaceCells cells to a front face moves away from it, both
  // within kMaxRelocation cells of its grid position; the probe then traces again from there
  // (once, in the same update) and is classified by those rays.
  bool relocate = false;
};

// Relocation keeps a probe this many of the smallest cell sizes off the surfaces it sees.
inline constexpr float kMinSurfaceCells = 0.1f;

// The nearest first hits of one probe's rays (front and back faces apart), for relocation.
struct NearestHits {
  float back = HUGE_VALF;
  glm::vec3 back_dir{0.0f};
  float front = HUGE_VALF;
  glm::vec3 front_dir{0.0f};
};

// Where relocation moves probe i of `volume` given its nearest hits and its classification:
// the new offset (clamped as ProbeVolume::set_offset does), or the old one when it stays.
glm::vec3 relocated_offset(const ProbeVolume& volume, std::uint32_t i, const NearestHits& hits,
                           bool inside_geometry);

// Throws std::invalid_argument for samples == 0, hysteresis outside [0, 1) or a threshold
// outside [0, 1].
void check_update_options(const UpdateOptions& options);

struct UpdateStats {
  std::uint64_t frame = 0;            // the volume's update number this was
  std::uint32_t probes_traced = 0;    // probes that traced rays (classified ones included)
  std::uint32_t newly_inactive = 0;   // found inside geometry by this update
  std::uint64_t paths = 0;            // paths started from probes
  std::uint64_t rays = 0;             // rays the source cast (bounces and shadow rays included)
  std::uint64_t invalid_samples = 0;  // paths that returned non-finite radiance (dropped as 0)
  double seconds = 0.0;

  double mrays_per_second() const { return seconds > 0.0 ? double(rays) / seconds * 1e-6 : 0.0; }
};

// The probe update on the CPU: paths from a RadianceSource, parallel over probes.
class ProbeTracer final : public ProbeUpdater {
 public:
  ProbeTracer(const RadianceSource& source, const UpdateOptions& options);

  const UpdateOptions& options() const override { return options_; }
  void set_options(const UpdateOptions& options) override;

  // One update of every active probe of the volume.
  UpdateStats update(ProbeVolume& volume) const { return update_all(volume); }
  // One update of the listed probes (the scheduler's choice); inactive ones are skipped.
  // Every probe still ages by one; the updated ones restart at age 0.
  UpdateStats update(ProbeVolume& volume, std::span<const std::uint32_t> probes) const override;

  // The SH projection of one probe's rays for the volume's update number `frame`, without
  // touching the volume (the estimate has the volume's order). Returns the number of back-face
  // first hits; adds the paths dropped for non-finite radiance to *invalid when given; bins the
  // rays' first-hit distances into *moments when given (cleared first; the volume's range).
  std::uint32_t trace_probe(const ProbeVolume& volume, std::uint32_t probe, std::uint64_t frame,
                            sh::ShRgb& estimate, std::uint64_t* invalid = nullptr,
                            MomentEstimate* moments = nullptr, NearestHits* nearest = nullptr) const;

 private:
  const RadianceSource& source_;
  UpdateOptions options_;
  // The unrotated Fibonacci lattice of options_.samples directions, computed once rather than
  // at every path (its double-precision trigonometry was ~1 % of an update).
  std::vector<glm::vec3> lattice_;
};

}  // namespace ddish::probes
