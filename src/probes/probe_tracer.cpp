#include "probes/probe_tracer.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "probes/fibonacci.h"
#include "sh/projection.h"

namespace ddish::probes {

void check_update_options(const UpdateOptions& options) {
  if (options.samples == 0)
    throw std::invalid_argument("probe samples must be at least 1");
  check_hysteresis(options.hysteresis);
  if (!(options.backface_threshold >= 0.0f && options.backface_threshold <= 1.0f))
    throw std::invalid_argument("back-face threshold must be in [0, 1], got " +
                                std::to_string(options.backface_threshold));
}

namespace {

std::vector<glm::vec3> fibonacci_lattice(std::uint32_t n) {
  std::vector<glm::vec3> lattice(n);
  for (std::uint32_t i = 0; i < n; ++i) lattice[i] = fibonacci_direction(i, n);
  return lattice;
}

}  // namespace

ProbeTracer::ProbeTracer(const RadianceSource& source, const UpdateOptions& options)
    : source_(source), options_(options) {
  check_update_options(options);
  lattice_ = fibonacci_lattice(options.samples);
}

void ProbeTracer::set_options(const UpdateOptions& options) {
  check_update_options(options);
  if (options.samples != options_.samples)
    lattice_ = fibonacci_lattice(options.samples);
  options_ = options;
}

std::uint32_t ProbeTracer::trace_probe(const ProbeVolume& volume, std::uint32_t probe,
                                       std::uint64_t frame, sh::ShRgb& estimate,
                                       std::uint64_t* invalid, MomentEstimate* moments,
                                       NearestHits* nearest) const {
  const std::uint32_t n = options_.samples;
  // Each lattice direction stands for an equal share 4π/N of the sphere.
  const float weight = sh::uniform_sphere_weight(n);

  // The probe's own stream for this update: independent of the thread that runs it.
  trace::Sampler sampler(options_.seed, probe, frame);
  const glm::mat3 rotation = random_rotation(sampler);
  const glm::vec3 origin = volume.position(probe);
  // Each ray stands for a cone of solid angle 4π/N: textures are looked up at that footprint's
  // mip level, which is also what the probe's SH can resolve.
  const float cone_spread = std::sqrt(weight);

  sh::ShProjector projector(volume.sh_order());
  if (moments) moments->clear();
  if (nearest) *nearest = NearestHits{};
  const float range = volume.moment_range();
  std::uint32_t backfaces = 0;
  for (std::uint32_t i = 0; i < n; ++i) {
    trace::Ray ray;
    ray.origin = origin;
    ray.cone_spread = cone_spread;
    ray.direction = glm::normalize(rotation * lattice_[i]);
    trace::PathSample s = source_.trace_path(ray, sampler);
    if (s.hit && s.backface) ++backfaces;
    if (nearest && s.hit) {
      float& d = s.backface ? nearest->back : nearest->front;
      if (s.hit_distance < d) {
        d = s.hit_distance;
        (s.backface ? nearest->back_dir : nearest->front_dir) = ray.direction;
      }
    }
    // The distance is geometry: valid even when the path's radiance is not.
    if (moments) moments->add(ray.direction, s.hit ? s.hit_distance : HUGE_VALF, range);
    const glm::vec3 L = s.radiance;
    if (!std::isfinite(L.x) || !std::isfinite(L.y) || !std::isfinite(L.z)) {
      // One NaN would poison the running average for good; drop the path and report it.
      if (invalid) ++*invalid;
      continue;
    }
    projector.add(ray.direction, L, weight);
  }
  estimate = projector.result();
  return backfaces;
}

glm::vec3 relocated_offset(const ProbeVolume& volume, std::uint32_t i, const NearestHits& hits,
                           bool inside_geometry) {
  const glm::vec3 spacing = volume.grid().spacing();
  const float cell = volume.grid().smallest_spacing();
  const glm::vec3 old = volume.offset(i);
  if (!(cell > 0.0f)) return old;
  const float keep = kMinSurfaceCells * cell;
  glm::vec3 moved = old;
  if (inside_geometry && std::isfinite(hits.back))
    moved = old + hits.back_dir * (hits.back + keep);  // through the nearest back face
  else if (!inside_geometry && hits.front < keep)
    moved = old - hits.front_dir * (keep - hits.front);  // away from the nearest front face
  const glm::vec3 bound = kMaxRelocation * spacing;
  return glm::clamp(moved, -bound, bound);
}

UpdateStats ProbeTracer::update(ProbeVolume& volume, std::span<const std::uint32_t> probes) const {
  // Inactive and repeated probes are left out before any work is split.
  const std::vector<std::uint32_t> work = probes_to_update(volume, probes);

  volume.begin_update();
  UpdateStats stats;
  stats.frame = volume.frame();
  stats.probes_traced = std::uint32_t(work.size());
  stats.paths = std::uint64_t(work.size()) * options_.samples;

  const std::uint64_t rays_before = source_.rays_traced();
  const auto start = std::chrono::steady_clock::now();
  std::atomic<std::uint32_t> newly_inactive{0};
  std::atomic<std::uint64_t> invalid{0};

  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, work.size(), 1),
                    [&](const tbb::blocked_range<std::size_t>& range) {
    sh::ShRgb estimate(volume.sh_order());
    MomentEstimate moments(volume.moment_resolution());
    MomentEstimate* gather = volume.has_moments() ? &moments : nullptr;
    std::uint64_t local_invalid = 0;
    for (std::size_t w = range.begin(); w != range.end(); ++w) {
      const std::uint32_t p = work[w];
      ProbeState& state = volume.state(p);
      const bool relocating = options_.relocate && state.unclassified();
      NearestHits nearest;
      std::uint32_t backfaces = trace_probe(volume, p, stats.frame, estimate, &local_invalid,
                                            gather, relocating ? &nearest : nullptr);
      if (state.unclassified()) {
        Classification c = classify(backfaces, options_.samples, options_.backface_threshold);
        if (relocating) {
          const glm::vec3 moved = relocated_offset(volume, p, nearest, c.inside_geometry);
          if (moved != volume.offset(p)) {
            // Each probe's offset belongs to its one task, as its coefficients do.
            volume.set_offset(p, moved);
            backfaces = trace_probe(volume, p, stats.frame, estimate, &local_invalid, gather);
            c = classify(backfaces, options_.samples, options_.backface_threshold);
          }
        }
        state.backface_fraction = c.backface_fraction;
        state.flags = std::uint8_t(state.flags & ~kProbeUnclassified);
        if (c.inside_geometry) {
          volume.deactivate(p, true);
          state.age = 0;
          newly_inactive.fetch_add(1, std::memory_order_relaxed);
          continue;
        }
      }
      // Each probe's state and coefficients belong to exactly one task: no locking needed.
      volume.accumulate(p, estimate, options_.samples, options_.hysteresis, options_.blend,
                        options_.reference_samples, gather);
    }
    invalid.fetch_add(local_invalid, std::memory_order_relaxed);
  });

  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  stats.rays = source_.rays_traced() - rays_before;
  stats.newly_inactive = newly_inactive.load();
  stats.invalid_samples = invalid.load();
  return stats;
}

}  // namespace ddish::probes
