#include "net/bricks.h"

#include <charconv>
#include <cstdio>
#include <stdexcept>

#include "probes/frustum.h"

namespace ddish::net {

BrickLayout::BrickLayout(const probes::ProbeGrid& grid)
    : grid_(grid), bricks_((grid.counts() + glm::ivec3(kBrickEdge - 1)) / kBrickEdge) {}

std::uint32_t BrickLayout::brick_count() const {
  return std::uint32_t(bricks_.x) * std::uint32_t(bricks_.y) * std::uint32_t(bricks_.z);
}

std::uint32_t BrickLayout::brick_of(std::uint32_t probe) const {
  const glm::ivec3 b = grid_.cell(probe) / kBrickEdge;
  return std::uint32_t(b.x + bricks_.x * (b.y + bricks_.y * b.z));
}

std::vector<std::uint32_t> BrickLayout::probes(std::uint32_t brick) const {
  const glm::ivec3 b(int(brick % std::uint32_t(bricks_.x)), int((brick / std::uint32_t(bricks_.x)) % std::uint32_t(bricks_.y)),
                     int(brick / (std::uint32_t(bricks_.x) * std::uint32_t(bricks_.y))));
  const glm::ivec3 lo = b * kBrickEdge, hi = glm::min(lo + kBrickEdge, grid_.counts());
  std::vector<std::uint32_t> out;
  for (int z = lo.z; z < hi.z; ++z)
    for (int y = lo.y; y < hi.y; ++y)
      for (int x = lo.x; x < hi.x; ++x) out.push_back(grid_.index({x, y, z}));
  return out;
}

bool BrickLayout::needed(std::uint32_t brick, std::span<const scene::View> views, float margin) const {
  if (views.empty()) return true;
  const std::vector<std::uint32_t> p = probes(brick);
  const glm::ivec3 lo = grid_.cell(p.front()), hi = grid_.cell(p.back());
  constexpr float kFar = 1e6f;  // past a grid face: the border probes shade everything beyond it
  scene::Aabb box{grid_.position(lo - 1), grid_.position(hi + 1)};
  for (int a = 0; a < 3; ++a) {
    if (lo[a] == 0) box.min[a] = -kFar;
    if (hi[a] == grid_.counts()[a] - 1) box.max[a] = kFar;
  }
  for (const scene::View& v : views)
    if (probes::Frustum(v).intersects(box, margin)) return true;
  return false;
}

std::vector<std::uint32_t> BrickLayout::needed(std::span<const scene::View> views, float margin) const {
  std::vector<std::uint32_t> out;
  for (std::uint32_t b = 0; b < brick_count(); ++b)
    if (needed(b, views, margin)) out.push_back(b);
  return out;
}

std::string brick_topic(std::uint32_t brick) {
  char text[16];
  std::snprintf(text, sizeof text, "b%08x", brick);
  return text;
}

std::optional<std::uint32_t> parse_brick_topic(std::span<const std::uint8_t> topic) {
  if (topic.size() != kTopicBytes || topic[0] != 'b') return std::nullopt;
  std::uint32_t value = 0;
  for (std::size_t k = 1; k < kTopicBytes; ++k) {
    const std::uint8_t c = topic[k];
    const int digit = c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : -1;
    if (digit < 0) return std::nullopt;
    value = value * 16 + std::uint32_t(digit);
  }
  return value;
}

BrickShare parse_brick_share(const std::string& text) {
  const std::size_t slash = text.find('/');
  BrickShare s;
  const auto number = [&](std::size_t from, std::size_t to, std::uint32_t& out) {
    const auto [end, ec] = std::from_chars(text.data() + from, text.data() + to, out);
    return ec == std::errc() && end == text.data() + to && to > from;
  };
  if (slash == std::string::npos || !number(0, slash, s.index) || !number(slash + 1, text.size(), s.of) ||
      s.of < 1 || s.of > 4096 || s.index >= s.of)
    throw std::invalid_argument("--bricks must be I/N with 0 <= I < N <= 4096, got '" + text + "'");
  return s;
}

}  // namespace ddish::net
