#include "probes/moment_map.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace ddish::probes {

void check_moment_resolution(int resolution) {
  if (resolution < 0 || resolution > kMaxMomentResolution)
    throw std::invalid_argument("probe visibility map resolution must be 0 (off) .. " +
                                std::to_string(kMaxMomentResolution) + ", got " +
                                std::to_string(resolution));
}

namespace {
// sign() that never returns 0, so directions on the coordinate planes fold consistently.
float sign_not_zero(float v) { return v >= 0.0f ? 1.0f : -1.0f; }
}  // namespace

glm::vec2 octahedral_encode(const glm::vec3& dir) {
  const float l1 = std::abs(dir.x) + std::abs(dir.y) + std::abs(dir.z);
  glm::vec2 p = l1 > 0.0f ? glm::vec2(dir.x, dir.y) / l1 : glm::vec2(0.0f);
  if (dir.z < 0.0f) {
    p = glm::vec2((1.0f - std::abs(p.y)) * sign_not_zero(p.x),
                  (1.0f - std::abs(p.x)) * sign_not_zero(p.y));
  }
  return p;
}

std::uint32_t moment_texel(const glm::vec3& dir, int resolution) {
  const glm::vec2 uv = octahedral_encode(dir) * 0.5f + 0.5f;
  const int last = resolution - 1;
  const int x = std::clamp(int(uv.x * float(resolution)), 0, last);
  const int y = std::clamp(int(uv.y * float(resolution)), 0, last);
  return std::uint32_t(x + resolution * y);
}

MomentEstimate::MomentEstimate(int res) : resolution(res) {
  check_moment_resolution(res);
  clear();
}

void MomentEstimate::clear() {
  const std::size_t n = std::size_t(resolution) * std::size_t(resolution);
  sum.assign(n, glm::vec2(0.0f));
  count.assign(n, 0u);
}

void MomentEstimate::add(const glm::vec3& dir, float distance, float range) {
  if (resolution == 0) return;
  // Clamped: no interpolated point lies farther than the range from a probe it reads, so
  // distances beyond it change no weight, and bounded values keep the variance finite.
  const float d = std::isfinite(distance) ? std::min(std::max(distance, 0.0f), range) / range : 1.0f;
  const std::uint32_t t = moment_texel(dir, resolution);
  sum[t] += glm::vec2(d, d * d);
  count[t] += 1;
}

}  // namespace ddish::probes
