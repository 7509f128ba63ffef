#include "probes/accumulation.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace ddish::probes {

void check_hysteresis(float alpha) {
  if (!(alpha >= 0.0f && alpha < 1.0f))
    throw std::invalid_argument("hysteresis must be in [0, 1), got " + std::to_string(alpha));
}

float blend_weight(std::uint32_t k, float alpha) {
  if (k == 0) return 1.0f;  // defensive: the first update always replaces the (zero) start
  return std::max(1.0f / float(k), 1.0f - alpha);
}

const char* blend_rule_name(BlendRule rule) {
  switch (rule) {
    case BlendRule::per_update: return "per-update";
    case BlendRule::per_sample: return "per-sample";
  }
  return "per-update";
}

BlendRule parse_blend_rule(const std::string& name) {
  if (name == "per-update") return BlendRule::per_update;
  if (name == "per-sample") return BlendRule::per_sample;
  throw std::invalid_argument("unknown blend rule '" + name + "' (per-update or per-sample)");
}

namespace {

// N_alpha = S * alpha / (1 - alpha): the history, in samples, that an exponential average with
// hysteresis alpha keeps when every update holds S samples. Computed in double: near alpha = 1
// the ratio is large and the float division would lose the small weights it produces.
double history_cap(float alpha, std::uint32_t reference_samples) {
  return double(reference_samples) * double(alpha) / (1.0 - double(alpha));
}

}  // namespace

float sample_blend_weight(const BlendHistory& history, std::uint64_t new_samples, float alpha,
                          std::uint32_t reference_samples) {
  if (history.samples == 0 || new_samples == 0) return history.samples == 0 ? 1.0f : 0.0f;
  // Every frame without an update the cap shrinks by alpha, as the history of a probe updated
  // every frame would have been down-weighted by alpha per frame.
  const std::uint32_t missed = history.age > 1 ? history.age - 1 : 0;
  const double cap = history_cap(alpha, reference_samples) * std::pow(double(alpha), double(missed));
  const double h = std::min(double(history.samples), cap);
  const double n = double(new_samples);
  return float(n / (h + n));
}

float blend_weight(BlendRule rule, const BlendHistory& history, std::uint64_t new_samples,
                   float alpha, std::uint32_t reference_samples) {
  if (rule == BlendRule::per_sample)
    return sample_blend_weight(history, new_samples, alpha, reference_samples);
  return blend_weight(history.updates + 1, alpha);
}

float sample_equivalent_hysteresis(float alpha, std::uint32_t reference_samples,
                                   std::uint32_t samples) {
  if (samples == reference_samples || samples == 0) return alpha;
  // 1 - alpha' = n / (N_alpha + n)  <=>  alpha' = N_alpha / (N_alpha + n).
  const double cap = history_cap(alpha, reference_samples);
  const double a = cap / (cap + double(samples));
  // Stay inside the valid range [0, 1) even when rounding to float lands on 1.
  return std::min(float(a), std::nextafter(1.0f, 0.0f));
}

}  // namespace ddish::probes
