// The reference renderer: converged path-traced images of a scene::View, the ground truth for
// every error figure ddish reports (DESIGN.md "one path tracer, two uses"). It drives the same
// Tracer as the probe tracer, per pixel, and knows nothing about image files or metrics: it
// produces a linear float RGB buffer that the command line converts and writes.
//
// Sampling:
// - Pixel filter by filter importance sampling: each sample's position is the pixel centre plus
//   an offset drawn from the filter itself, and every sample has weight 1, so the image is the
//   filtered radiance without the negative-lobe and normalisation problems of splatting. The
//   filter is a radially symmetric Gaussian, sigma = 0.5 px, truncated to a disk of radius
//   1.5 px (3 sigma, 1.1% of the mass cut off), sampled exactly by inverting its radial CDF.
// - Progressive passes: after pass k every pixel holds 2^k samples (1, 2, 4, 8, ...; the last
//   pass stops at the requested count), so a time limit stops cleanly with a finished image:
//   a pass that would end after the limit (estimated from the time per sample so far) is not
//   started, and one that runs past it anyway (a loaded machine) is abandoned and discarded.
//   The image is always the last completed pass; the first pass always completes.
// - Determinism: sample s of pixel p uses Sampler(seed, stream = p, index = s), where
//   p = y * width + x and s counts from 0 over all passes. The image therefore depends only on
//   the seed and the sample count, not on threads, tiles or how the samples were split in passes.
// - Samples with a NaN or infinite channel are dropped and counted; a pixel is the mean of its
//   finite samples. (The Tracer already replaces a NaN, infinite or negative path by zero and
//   counts it, Tracer::invalid_paths; those are reported separately, as they stay in the mean.)
// - Camera rays have cone_spread 0: textures are read at their finest level and the pixel
//   filter's supersampling does the antialiasing, as a ground truth should.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "scene/view.h"

namespace ddish::trace {

class Tracer;

struct ReferenceOptions {
  int spp = 256;                // samples per pixel to reach
  double time_limit_s = 0.0;    // > 0: stop at the last pass completed within this (seconds)
  std::uint64_t seed = 1;
  float filter_sigma = 0.5f;    // pixel filter (pixels)
  float filter_radius = 1.5f;
  int tile_size = 16;           // pixels per tile side (parallel work unit)
  double progress_interval_s = 0.1;  // least time between two progress reports
};

struct ReferenceProgress {
  double fraction = 0.0;   // of the work (samples, or the time limit if that ends it first)
  double elapsed_s = 0.0;
  int spp_done = 0;        // samples per pixel in finished passes
  int spp_target = 0;
};

struct ReferenceImage {
  int width = 0;
  int height = 0;
  std::vector<glm::vec3> pixels;  // row-major, row 0 = top; linear radiance
  int spp = 0;                    // samples per pixel reached
  double seconds = 0.0;           // wall-clock render time, an abandoned pass included
                                  // (pass_done callbacks excluded)
  std::uint64_t rays = 0;         // rays the tracer cast for this image (Tracer::rays_traced)
  std::uint64_t nonfinite_samples = 0;  // NaN/Inf samples dropped here
  std::uint64_t invalid_paths = 0;      // paths the Tracer flagged and zeroed during the render
  bool time_limited = false;      // stopped before spp by the time limit
};

struct ReferenceCallbacks {
  // Called now and then from a worker thread (at most one call at a time, at most every
  // progress_interval_s; its time counts as render time)
  // and once from the calling thread when the render ends with fraction 1.
  std::function<void(const ReferenceProgress&)> progress;
  // Called on the calling thread after every pass with the image so far (spp = samples in it),
  // for convergence curves. Only when set is the intermediate image assembled.
  std::function<void(const ReferenceImage&)> pass_done;
};

// The accumulated sample counts after each pass for a target of spp samples per pixel:
// 1, 2, 4, ... up to spp, which is always the last entry (e.g. 6 -> 1, 2, 4, 6).
std::vector<int> pass_schedule(int spp);

// A pixel-filter offset (pixels, relative to the pixel centre) from a uniform point u in [0,1)^2.
glm::vec2 sample_pixel_filter(const glm::vec2& u, float sigma, float radius);

// Renders the view. Throws std::invalid_argument for an empty view, spp < 1 or a bad filter.
ReferenceImage render_reference(const Tracer& tracer, const scene::View& view,
                                const ReferenceOptions& options,
                                const ReferenceCallbacks& callbacks = {});

}  // namespace ddish::trace
