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
#pragma once

#include <cstdint>

namespace ddish::probes {

inline constexpr float kDefaultHysteresis = 0.95f;

// Throws std::invalid_argument unless 0 <= alpha < 1.
void check_hysteresis(float alpha);

// The weight w_k of the k-th update (k >= 1) of a probe; see above.
float blend_weight(std::uint32_t k, float alpha);

}  // namespace ddish::probes
