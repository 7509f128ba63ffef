// Temporal accumulation of probe updates into the fp32 running average.
//
// Update k (1-based) of a probe blends its new estimate e_k into the average A with weight w_k:
//   A_k = (1 - w_k) A_{k-1} + w_k e_k,   w_k = max(1/k, 1 - alpha).
// While 1/k >= 1 - alpha this is the exact mean of all updates so far (a fresh probe converges
// as fast as plain Monte Carlo, with no bias towards its zero start); afterwards it is an
// exponential moving average with hysteresis alpha that forgets old light (moving lights and
// objects) with a time constant of about 1 / (1 - alpha) updates.
//
// Default alpha = 0.95: in steady state the average has the variance of a mean over
// (1 + alpha) / (1 - alpha) = 39 updates (about 10,000 rays at 256 per update, quiet enough for
// L2 diffuse light), while a change in the lighting is 64% through after 20 updates and 95%
// after 60 (one second at 60 updates per second). DDISH-GI's 0.99 is 2.2x quieter but takes five
// seconds to follow a light switch. fp32 keeps small weights exact (fp16 would stall, DESIGN.md).
//
// Sample-aware blending (BlendRule::per_sample), for scheduled updates where a probe may get
// fewer samples than usual in a frame, or may not be updated for many frames. The weight counts
// samples instead of updates:
//   w = n / (h + n),   h = min(H, N_alpha * alpha^(age - 1)),   N_alpha = S * alpha / (1 - alpha)
// n: the new estimate's samples; H: the samples blended into the average so far; S: the
// reference sample count (the configured --probe-samples); age: frames since the probe's last
// update, counting this one (1 = updated every frame).
// - While H < N_alpha it is the exact mean over all samples so far, whatever each update held.
// - N_alpha caps the history at what the hysteresis keeps: with n = S every frame the weight is
//   exactly max(1/k, 1 - alpha), so a probe updated every frame at full samples behaves as
//   with the per-update rule (that is the uniform schedule's published behaviour).
// - An update with fewer samples (n < S) gets a proportionally smaller weight, so a cheap,
//   noisy estimate does not add more noise to a converged probe than its samples justify.
// - The cap decays by alpha per frame the probe was not updated, as an exponential average that
//   forgets alpha per frame would have forgotten its history: a probe left out for many frames
//   (off-screen, low priority) lets new light replace its stale light faster instead of
//   smearing it over another 1 / (1 - alpha) updates.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace ddish::probes {

inline constexpr float kDefaultHysteresis = 0.95f;

// Throws std::invalid_argument unless 0 <= alpha < 1.
void check_hysteresis(float alpha);

// The weight w_k of the k-th update (k >= 1) of a probe; see above.
float blend_weight(std::uint32_t k, float alpha);

enum class BlendRule {
  per_update,  // w = max(1/k, 1 - alpha): the published rule and the default
  per_sample,  // w = n / (h + n) with the capped, age-decayed sample history (see above)
};

// "per-update" / "per-sample"; parse_blend_rule throws std::invalid_argument naming the choices.
const char* blend_rule_name(BlendRule rule);
BlendRule parse_blend_rule(const std::string& name);

// What a probe's running average holds before an update is blended in.
struct BlendHistory {
  std::uint32_t updates = 0;  // updates blended so far
  std::uint64_t samples = 0;  // their samples (H)
  std::uint32_t age = 1;      // frames since the last update, counting this one (>= 1)
};

// The per-sample weight w = n / (h + n) (see above): 1 for an empty history; reference_samples
// is S, the sample count at which the rule reproduces the hysteresis.
float sample_blend_weight(const BlendHistory& history, std::uint64_t new_samples, float alpha,
                          std::uint32_t reference_samples);

// The weight of the next update under either rule (per_update uses history.updates + 1).
float blend_weight(BlendRule rule, const BlendHistory& history, std::uint64_t new_samples,
                   float alpha, std::uint32_t reference_samples);

// The hysteresis that gives an update of `samples` paths the steady-state weight the
// per-sample rule would give it, n / (N_alpha + n), through the per-update rule: a whole frame
// traced at a reduced sample count can pass this as UpdateOptions::hysteresis. Equals alpha
// when samples == reference_samples.
float sample_equivalent_hysteresis(float alpha, std::uint32_t reference_samples,
                                   std::uint32_t samples);

}  // namespace ddish::probes
