#include "trace/reference.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <numbers>
#include <stdexcept>

#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include "trace/sampler.h"
#include "trace/tracer.h"

namespace ddish::trace {

std::vector<int> pass_schedule(int spp) {
  if (spp < 1) throw std::invalid_argument("samples per pixel must be at least 1");
  std::vector<int> passes;
  for (long long n = 1; n < spp; n *= 2) passes.push_back(static_cast<int>(n));
  passes.push_back(spp);
  return passes;
}

glm::vec2 sample_pixel_filter(const glm::vec2& u, float sigma, float radius) {
  // Radial density of a 2D Gaussian: p(r) ∝ r exp(-r^2 / 2 sigma^2), whose CDF on [0, R] is
  // (1 - exp(-r^2 / 2 sigma^2)) / (1 - exp(-R^2 / 2 sigma^2)); inverting it gives r exactly.
  const double s2 = 2.0 * double(sigma) * double(sigma);
  const double mass = 1.0 - std::exp(-double(radius) * double(radius) / s2);
  const double r = std::sqrt(-s2 * std::log1p(-double(u.x) * mass));
  const double phi = 2.0 * std::numbers::pi * double(u.y);
  return {static_cast<float>(r * std::cos(phi)), static_cast<float>(r * std::sin(phi))};
}

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Per-pixel running sums over all finished passes. Double sums keep thousands of samples of
// very different magnitude exact enough; the count excludes dropped (non-finite) samples.
struct Accumulator {
  std::vector<glm::dvec3> sum;
  std::vector<std::uint32_t> count;
};

void resolve(const Accumulator& acc, ReferenceImage& out) {
  out.pixels.resize(acc.sum.size());
  for (std::size_t i = 0; i < acc.sum.size(); ++i)
    out.pixels[i] = acc.count[i] ? glm::vec3(acc.sum[i] / double(acc.count[i])) : glm::vec3(0.0f);
}

}  // namespace

ReferenceImage render_reference(const Tracer& tracer, const scene::View& view,
                                const ReferenceOptions& options,
                                const ReferenceCallbacks& callbacks) {
  if (view.width <= 0 || view.height <= 0)
    throw std::invalid_argument("reference view has no pixels");
  if (!(options.filter_sigma > 0.0f) || !(options.filter_radius > 0.0f))
    throw std::invalid_argument("pixel filter needs sigma > 0 and radius > 0");
  const std::vector<int> schedule = pass_schedule(options.spp);
  const int w = view.width;
  const int h = view.height;
  const std::size_t npix = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
  const int tile = std::max(1, options.tile_size);

  Accumulator acc{std::vector<glm::dvec3>(npix, glm::dvec3(0.0)),
                  std::vector<std::uint32_t>(npix, 0u)};
  // The pass being rendered goes to its own buffer and joins acc only once complete, so a pass
  // abandoned at the time limit leaves no trace in the image.
  Accumulator pass{std::vector<glm::dvec3>(npix, glm::dvec3(0.0)),
                   std::vector<std::uint32_t>(npix, 0u)};
  ReferenceImage out;
  out.width = w;
  out.height = h;

  const Clock::time_point t0 = Clock::now();
  const std::uint64_t rays0 = tracer.rays_traced();
  const std::uint64_t invalid0 = tracer.invalid_paths();
  const double total_samples = double(npix) * double(options.spp);
  std::atomic<std::uint64_t> samples_done{0};  // pixel samples over all passes
  std::uint64_t nonfinite = 0;                 // in completed passes
  std::atomic<std::uint64_t> pass_nonfinite{0};
  std::atomic<bool> out_of_time{false};
  std::mutex progress_mutex;
  std::atomic<double> last_report{0.0};
  // Time spent in pass_done callbacks (a convergence curve computes metrics there) is not
  // render time: it is left out of the reported seconds, Mrays/s and the time limit.
  double paused_s = 0.0;
  auto render_time = [&] { return seconds_since(t0) - paused_s; };

  auto fraction_now = [&](double elapsed) {
    double f = double(samples_done.load(std::memory_order_relaxed)) / total_samples;
    if (options.time_limit_s > 0.0) f = std::max(f, elapsed / options.time_limit_s);
    // Only the final report says 1: a display may take 1 to mean "finished".
    return std::min(f, 0.999);
  };
  auto maybe_report = [&](int spp_done) {
    if (!callbacks.progress) return;
    double now = render_time();
    double last = last_report.load(std::memory_order_relaxed);
    if (now - last < options.progress_interval_s) return;
    std::unique_lock lock(progress_mutex, std::try_to_lock);
    if (!lock.owns_lock() || !last_report.compare_exchange_strong(last, now)) return;
    callbacks.progress({fraction_now(now), now, spp_done, options.spp});
  };

  int done = 0;
  for (int target : schedule) {
    const int count = target - done;
    if (done > 0 && options.time_limit_s > 0.0) {
      // Every pass after the first costs about as many seconds per sample as the passes so far;
      // a pass that would end after the limit is not started, so the image is always a whole
      // number of passes.
      double elapsed = render_time();
      double estimate = elapsed / double(done) * double(count);
      if (elapsed + estimate > options.time_limit_s) {
        out.time_limited = true;
        break;
      }
    }

    // The first pass always completes (an image needs a sample); later ones stop when the
    // estimate above was wrong (a loaded machine) and the limit passes during the pass.
    const bool abortable = done > 0 && options.time_limit_s > 0.0;
    pass_nonfinite = 0;
    tbb::parallel_for(
        tbb::blocked_range2d<int>(0, h, tile, 0, w, tile),
        [&](const tbb::blocked_range2d<int>& r) {
          std::uint64_t bad = 0;
          for (int y = r.rows().begin(); y < r.rows().end(); ++y) {
            if (abortable && (out_of_time.load(std::memory_order_relaxed) ||
                              render_time() > options.time_limit_s)) {
              out_of_time.store(true, std::memory_order_relaxed);
              return;
            }
            for (int x = r.cols().begin(); x < r.cols().end(); ++x) {
              const std::size_t p = static_cast<std::size_t>(y) * static_cast<std::size_t>(w) +
                                    static_cast<std::size_t>(x);
              glm::dvec3 sum(0.0);
              std::uint32_t valid = 0;
              for (int s = done; s < target; ++s) {
                Sampler sampler(options.seed, p, static_cast<std::uint64_t>(s));
                glm::vec2 off = sample_pixel_filter(sampler.next2d(), options.filter_sigma,
                                                    options.filter_radius);
                scene::Ray cam = scene::view_ray(view, float(x) + 0.5f + off.x,
                                                 float(y) + 0.5f + off.y);
                Ray ray;
                ray.origin = cam.origin;
                ray.direction = cam.direction;
                glm::vec3 l = tracer.trace_path(ray, sampler).radiance;
                if (std::isfinite(l.x) && std::isfinite(l.y) && std::isfinite(l.z)) {
                  sum += glm::dvec3(l);
                  ++valid;
                } else {
                  ++bad;
                }
              }
              // Each pixel belongs to exactly one tile, so no two threads touch it.
              pass.sum[p] = sum;
              pass.count[p] = valid;
            }
          }
          if (bad) pass_nonfinite.fetch_add(bad, std::memory_order_relaxed);
          samples_done.fetch_add(static_cast<std::uint64_t>(r.rows().size()) *
                                     static_cast<std::uint64_t>(r.cols().size()) *
                                     static_cast<std::uint64_t>(count),
                                 std::memory_order_relaxed);
          maybe_report(done);
        },
        tbb::simple_partitioner());
    if (out_of_time.load()) {
      out.time_limited = true;
      break;
    }
    for (std::size_t i = 0; i < npix; ++i) {
      acc.sum[i] += pass.sum[i];
      acc.count[i] += pass.count[i];
    }
    nonfinite += pass_nonfinite.load();
    done = target;

    if (callbacks.pass_done) {
      const Clock::time_point pause_start = Clock::now();
      ReferenceImage snapshot;
      snapshot.width = w;
      snapshot.height = h;
      snapshot.spp = done;
      snapshot.seconds = render_time();
      snapshot.rays = tracer.rays_traced() - rays0;
      snapshot.nonfinite_samples = nonfinite;
      snapshot.invalid_paths = tracer.invalid_paths() - invalid0;
      resolve(acc, snapshot);
      callbacks.pass_done(snapshot);
      paused_s += seconds_since(pause_start);
    }
  }

  out.spp = done;
  out.seconds = render_time();
  out.rays = tracer.rays_traced() - rays0;
  out.nonfinite_samples = nonfinite;
  out.invalid_paths = tracer.invalid_paths() - invalid0;
  resolve(acc, out);
  if (callbacks.progress) {
    std::lock_guard lock(progress_mutex);
    callbacks.progress({1.0, out.seconds, out.spp, options.spp});
  }
  return out;
}

}  // namespace ddish::trace
