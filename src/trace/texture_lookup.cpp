#include "trace/texture_lookup.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>

#include <tbb/parallel_for.h>

#include "scene/scene.h"
#include "trace/cpu_dispatch.h"

namespace ddish::trace {

namespace {

std::array<float, 256> make_srgb_table() {
  std::array<float, 256> table{};
  for (int i = 0; i < 256; ++i) {
    const float c = static_cast<float>(i) / 255.0f;
    table[static_cast<std::size_t>(i)] = c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
  }
  return table;
}

const std::array<float, 256> kSrgbTable = make_srgb_table();

int address(int i, int n, scene::Wrap mode) {
  switch (mode) {
    case scene::Wrap::ClampToEdge:
      return std::clamp(i, 0, n - 1);
    case scene::Wrap::MirroredRepeat: {
      int m = i % (2 * n);
      if (m < 0) m += 2 * n;
      return m < n ? m : 2 * n - 1 - m;
    }
    case scene::Wrap::Repeat:
      break;
  }
  const int m = i % n;
  return m < 0 ? m + n : m;
}

// Brings a coordinate into a small range with the same texels under `mode`, so that huge or
// non-finite coordinates cannot overflow the integer texel index.
float reduce(float x, scene::Wrap mode) {
  if (!std::isfinite(x)) return 0.0f;
  switch (mode) {
    case scene::Wrap::ClampToEdge:
      return std::clamp(x, -1.0f, 2.0f);
    case scene::Wrap::MirroredRepeat:
      return x - 2.0f * std::floor(0.5f * x);
    case scene::Wrap::Repeat:
      break;
  }
  return x - std::floor(x);
}

}  // namespace

float srgb_to_linear(std::uint8_t code) { return kSrgbTable[code]; }

MipTexture::MipTexture(const scene::Texture& texture) {
  if (texture.width <= 0 || texture.height <= 0 ||
      texture.rgba8.size() <
          static_cast<std::size_t>(texture.width) * static_cast<std::size_t>(texture.height) * 4u) {
    // An undecodable texture reads as opaque white, the glTF meaning of "no texture".
    static const std::uint8_t kWhite[4] = {255, 255, 255, 255};
    levels_.push_back({1, 1, kWhite});
    return;
  }
  levels_.push_back({texture.width, texture.height, texture.rgba8.data()});
  half_log2_texels_ =
      0.5f * std::log2(static_cast<float>(texture.width) * static_cast<float>(texture.height));
  while (levels_.back().width > 1 || levels_.back().height > 1) {
    const Level src = levels_.back();
    const int w = std::max(1, src.width / 2);
    const int h = std::max(1, src.height / 2);
    std::vector<std::uint8_t> dst(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 4u);
    for (int y = 0; y < h; ++y) {
      const int y0 = std::min(2 * y, src.height - 1);
      const int y1 = std::min(2 * y + 1, src.height - 1);
      for (int x = 0; x < w; ++x) {
        const int x0 = std::min(2 * x, src.width - 1);
        const int x1 = std::min(2 * x + 1, src.width - 1);
        for (int c = 0; c < 4; ++c) {
          auto at = [&](int xx, int yy) {
            return static_cast<int>(src.data[(static_cast<std::size_t>(yy) * src.width + xx) * 4 + c]);
          };
          const int sum = at(x0, y0) + at(x1, y0) + at(x0, y1) + at(x1, y1);
          dst[(static_cast<std::size_t>(y) * w + x) * 4 + c] = static_cast<std::uint8_t>((sum + 2) / 4);
        }
      }
    }
    storage_.push_back(std::move(dst));
    levels_.push_back({w, h, storage_.back().data()});
  }
}

namespace {

glm::vec4 decode(const std::uint8_t* p, bool srgb) {
  if (srgb) {
    return {kSrgbTable[p[0]], kSrgbTable[p[1]], kSrgbTable[p[2]], static_cast<float>(p[3]) / 255.0f};
  }
  return glm::vec4(p[0], p[1], p[2], p[3]) * (1.0f / 255.0f);
}

}  // namespace

glm::vec4 MipTexture::texel(int level, int x, int y, bool srgb, Wrap wrap) const {
  const Level& l = levels_[static_cast<std::size_t>(level)];
  return decode(l.data + (static_cast<std::size_t>(address(y, l.height, wrap.t)) * l.width +
                          static_cast<std::size_t>(address(x, l.width, wrap.s))) *
                             4,
                srgb);
}

DDISH_CPU_DISPATCH
glm::vec4 MipTexture::sample_level(glm::vec2 uv, int level, bool srgb, Wrap wrap,
                                   scene::Filter filter) const {
  const Level& l = levels_[static_cast<std::size_t>(level)];
  uv = {reduce(uv.x, wrap.s), reduce(uv.y, wrap.t)};
  if (filter == scene::Filter::Nearest) {  // the texel whose square holds uv
    const auto x = static_cast<int>(std::floor(uv.x * static_cast<float>(l.width)));
    const auto y = static_cast<int>(std::floor(uv.y * static_cast<float>(l.height)));
    return texel(level, x, y, srgb, wrap);
  }
  // Texel centres sit at half-integers.
  const float fx = uv.x * static_cast<float>(l.width) - 0.5f;
  const float fy = uv.y * static_cast<float>(l.height) - 0.5f;
  const float x0f = std::floor(fx);
  const float y0f = std::floor(fy);
  const float tx = fx - x0f;
  const float ty = fy - y0f;
  // The four texels' addresses are resolved once (the addressing modes cost integer divisions).
  const auto xi = static_cast<int>(x0f);
  const auto yi = static_cast<int>(y0f);
  const std::size_t x0 = static_cast<std::size_t>(address(xi, l.width, wrap.s)) * 4;
  const std::size_t x1 = static_cast<std::size_t>(address(xi + 1, l.width, wrap.s)) * 4;
  const std::size_t row = static_cast<std::size_t>(l.width) * 4;
  const std::uint8_t* r0 = l.data + static_cast<std::size_t>(address(yi, l.height, wrap.t)) * row;
  const std::uint8_t* r1 = l.data + static_cast<std::size_t>(address(yi + 1, l.height, wrap.t)) * row;
  const glm::vec4 a = glm::mix(decode(r0 + x0, srgb), decode(r0 + x1, srgb), tx);
  const glm::vec4 b = glm::mix(decode(r1 + x0, srgb), decode(r1 + x1, srgb), tx);
  return glm::mix(a, b, ty);
}

DDISH_CPU_DISPATCH
glm::vec4 MipTexture::sample(glm::vec2 uv, float lod, bool srgb, Wrap wrap) const {
  const float max_level = static_cast<float>(levels() - 1);
  lod = std::isfinite(lod) ? std::clamp(lod, 0.0f, max_level) : 0.0f;
  if (lod <= 0.0f) return sample_level(uv, 0, srgb, wrap, wrap.mag);
  switch (wrap.mip) {
    case scene::MipFilter::None:
      return sample_level(uv, 0, srgb, wrap, wrap.min);
    case scene::MipFilter::Nearest:  // Vulkan's nearest level: floor(lod + 0.5)
      return sample_level(uv, static_cast<int>(std::floor(lod + 0.5f)), srgb, wrap, wrap.min);
    case scene::MipFilter::Linear:
      break;
  }
  const int l0 = static_cast<int>(lod);
  const float t = lod - static_cast<float>(l0);
  const glm::vec4 a = sample_level(uv, l0, srgb, wrap, wrap.min);
  if (t <= 0.0f || l0 + 1 >= levels()) return a;
  return glm::mix(a, sample_level(uv, l0 + 1, srgb, wrap, wrap.min), t);
}

float MipTexture::footprint_log2(float width, float cos_theta, float uv_area, float world_area) {
  if (!(width > 0.0f) || !(uv_area > 0.0f) || !(world_area > 0.0f)) {
    return -std::numeric_limits<float>::infinity();
  }
  // Grazing footprints stretch by 1/cos; the floor keeps the level finite at cos = 0.
  const float uv_width = width * std::sqrt(uv_area / world_area) / std::max(std::abs(cos_theta), 0.05f);
  return std::log2(uv_width);
}

float MipTexture::lod_for_footprint(float width, float cos_theta, float uv_area, float world_area) const {
  return lod_for_footprint_log2(footprint_log2(width, cos_theta, uv_area, world_area));
}

TextureSet::TextureSet(const scene::Scene& scene) {
  std::vector<std::unique_ptr<MipTexture>> built(scene.textures.size());
  tbb::parallel_for(std::size_t{0}, scene.textures.size(),
                    [&](std::size_t i) { built[i] = std::make_unique<MipTexture>(scene.textures[i]); });
  textures_.reserve(built.size());
  for (auto& t : built) textures_.push_back(std::move(*t));
}

}  // namespace ddish::trace
