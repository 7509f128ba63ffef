#include "raster/roughness_mips.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace ddish::raster {

namespace {

constexpr int kRoughness = 1;  // glTF: G holds roughness, B metallic (R occlusion when packed)

std::uint8_t to_unorm8(float v) {
  return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
}

}  // namespace

std::vector<MipLevel> roughness_mip_chain(const scene::Texture& texture, float power) {
  if (!(power > 0.0f)) throw std::invalid_argument("roughness mip power must be > 0");
  const auto w0 = static_cast<std::uint32_t>(std::max(texture.width, 1));
  const auto h0 = static_cast<std::uint32_t>(std::max(texture.height, 1));
  if (texture.rgba8.size() != std::size_t{w0} * h0 * 4)
    throw std::invalid_argument("texture " + texture.name + " has " +
                                std::to_string(texture.rgba8.size()) + " bytes, not " +
                                std::to_string(std::size_t{w0} * h0 * 4));

  // Channels in the space they are averaged in: R, B, A linear, G as roughness^power.
  std::vector<std::array<float, 4>> cur(std::size_t{w0} * h0);
  for (std::size_t i = 0; i < cur.size(); ++i)
    for (int c = 0; c < 4; ++c) {
      const float v = texture.rgba8[4 * i + static_cast<std::size_t>(c)] / 255.0f;
      cur[i][static_cast<std::size_t>(c)] = c == kRoughness ? std::pow(v, power) : v;
    }

  std::vector<MipLevel> chain;
  chain.push_back({w0, h0, texture.rgba8});
  std::uint32_t w = w0, h = h0;
  while (w > 1 || h > 1) {
    const std::uint32_t nw = std::max(w / 2, 1u), nh = std::max(h / 2, 1u);
    std::vector<std::array<float, 4>> next(std::size_t{nw} * nh);
    MipLevel level{nw, nh, std::vector<std::uint8_t>(std::size_t{nw} * nh * 4)};
    for (std::uint32_t y = 0; y < nh; ++y)
      for (std::uint32_t x = 0; x < nw; ++x) {
        const std::uint32_t x0 = std::min(2 * x, w - 1), x1 = std::min(2 * x + 1, w - 1);
        const std::uint32_t y0 = std::min(2 * y, h - 1), y1 = std::min(2 * y + 1, h - 1);
        const std::size_t out = std::size_t{y} * nw + x;
        for (std::size_t c = 0; c < 4; ++c) {
          const float m = 0.25f * (cur[std::size_t{y0} * w + x0][c] + cur[std::size_t{y0} * w + x1][c] +
                                   cur[std::size_t{y1} * w + x0][c] + cur[std::size_t{y1} * w + x1][c]);
          next[out][c] = m;
          level.rgba8[4 * out + c] =
              to_unorm8(static_cast<int>(c) == kRoughness ? std::pow(m, 1.0f / power) : m);
        }
      }
    chain.push_back(std::move(level));
    cur = std::move(next);
    w = nw;
    h = nh;
  }
  return chain;
}

}  // namespace ddish::raster
