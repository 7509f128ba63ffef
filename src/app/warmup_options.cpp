#include "app/warmup_options.h"

#include <cmath>
#include <stdexcept>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

namespace ddish::app {

void add_warmup_options(CLI::App& cmd, WarmupOptions& options) {
  cmd.add_option("--warmup-ms", options.max_ms,
                 "probe warm-up before the first frame: every active probe traced round after round "
                 "for at most this long (within one round); 0: none")
      ->capture_default_str();
  cmd.add_option("--warmup-samples", options.samples,
                 "the warm-up ends once every active probe has this many samples")
      ->capture_default_str();
}

void check_warmup_options(const WarmupOptions& options) {
  if (!std::isfinite(options.max_ms) || options.max_ms < 0.0)
    throw std::invalid_argument(fmt::format("--warmup-ms must be >= 0, got {:g}", options.max_ms));
}

std::string describe_warmup(const WarmupReport& r, const WarmupOptions& o) {
  return fmt::format("warm-up: {} rounds over {} active probes, {} samples each, in {:.0f} ms{}", r.rounds,
                     r.probes, r.samples_per_probe, r.ms,
                     r.bounded ? fmt::format(" (stopped by --warmup-ms {:g} before {} samples)", o.max_ms, o.samples)
                               : std::string());
}

}  // namespace ddish::app
