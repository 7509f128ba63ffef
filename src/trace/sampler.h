// Deterministic random numbers for Monte-Carlo integration: PCG32 (O'Neill 2014), one
// independent stream per work item (pixel, probe), so results do not depend on how threads
// split the work.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

namespace ddish::trace {

class Sampler {
 public:
  // seed: the run's seed; stream: the work item (pixel index, probe index, ...);
  // index: the sample number within the item (each gets a decorrelated sequence).
  Sampler(std::uint64_t seed, std::uint64_t stream, std::uint64_t index = 0) {
    state_ = 0u;
    inc_ = (mix(stream ^ (index * 0x9E3779B97F4A7C15ull)) << 1u) | 1u;
    next_u32();
    state_ += mix(seed + index);
    next_u32();
  }

  std::uint32_t next_u32() {
    std::uint64_t old = state_;
    state_ = old * 6364136223846793005ull + inc_;
    auto xorshifted = static_cast<std::uint32_t>(((old >> 18u) ^ old) >> 27u);
    auto rot = static_cast<std::uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((~rot + 1u) & 31u));
  }

  // Uniform in [0, 1): 24 random bits, so 1.0f is never returned.
  float next1d() { return float(next_u32() >> 8) * 0x1p-24f; }
  glm::vec2 next2d() {
    float a = next1d();
    return {a, next1d()};
  }

 private:
  // SplitMix64 finaliser: spreads nearby seeds and stream ids over the whole state space.
  static std::uint64_t mix(std::uint64_t z) {
    z += 0x9E3779B97F4A7C15ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }

  std::uint64_t state_ = 0;
  std::uint64_t inc_ = 1;
};

}  // namespace ddish::trace
