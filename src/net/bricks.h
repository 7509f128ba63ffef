// Bricks: the probe grid cut into blocks of kBrickEdge^3 probes (smaller at the grid's far
// faces), the unit that servers own and clients subscribe to. The layout depends on the grid's
// counts only, so every server and client of one scene identity (which covers the grid) agrees
// on it without a word: brick (bx, by, bz) holds the probes whose cell is in
// [4 bx, 4 bx + 4) x [4 by, ...) x [4 bz, ...), and bricks are numbered x fastest, then y, then z.
// A brick's frames travel under the ZeroMQ topic "b" + 8 lowercase hex digits of its number:
// fixed width, so that a subscription (a prefix) matches exactly one brick.
// A server owns the bricks of a share I/N (`serve --bricks I/N`): brick b when b mod N == I,
// interleaved so that any view's probes are spread over all N servers.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "probes/probe_grid.h"
#include "scene/view.h"

namespace ddish::net {

inline constexpr int kBrickEdge = 4;
inline constexpr std::size_t kTopicBytes = 9;

class BrickLayout {
 public:
  explicit BrickLayout(const probes::ProbeGrid& grid);

  std::uint32_t brick_count() const;
  const glm::ivec3& bricks() const { return bricks_; }
  std::uint32_t brick_of(std::uint32_t probe) const;
  // The brick's probes, increasing.
  std::vector<std::uint32_t> probes(std::uint32_t brick) const;
  // Whether any view's frustum (widened by `margin` metres) meets the region whose shading uses
  // the brick's probes: its probes' box widened by one cell (trilinear interpolation reaches
  // the neighbouring cell), and without end past the grid's faces (points outside the grid
  // take the border probes).
  bool needed(std::uint32_t brick, std::span<const scene::View> views, float margin) const;
  // The bricks any view needs (increasing); all of them for no views.
  std::vector<std::uint32_t> needed(std::span<const scene::View> views, float margin) const;

 private:
  probes::ProbeGrid grid_;
  glm::ivec3 bricks_;
};

std::string brick_topic(std::uint32_t brick);
// The brick a topic names, or nullopt for anything that is not exactly "b" + 8 lowercase hex.
std::optional<std::uint32_t> parse_brick_topic(std::span<const std::uint8_t> topic);

// `serve --bricks I/N`: share I of N (0 <= I < N <= 4096).
struct BrickShare {
  std::uint32_t index = 0;
  std::uint32_t of = 1;
  bool owns(std::uint32_t brick) const { return brick % of == index; }
};
// Parses "I/N"; throws std::invalid_argument with the reason.
BrickShare parse_brick_share(const std::string& text);

}  // namespace ddish::net
