// Material textures as the tracer samples them: a box-filtered RGBA8 mip chain per scene texture,
// lookups with the glTF sampler's filters (trilinear by default) and addressing (repeat, clamp,
// mirrored repeat), and sRGB decoding per texel before filtering (so filtered colours are averages of linear values, as the
// GPU's sRGB formats do). Mips stay RGBA8 to keep memory sane on texture-heavy scenes (Sponza: 49
// textures of up to 2048²): level 0 is the scene's own pixel data, the smaller levels add a third.
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace ddish::trace {

// Addressing outside [0, 1] in u (s) and v (t), and the glTF sampler's filters: `mag` where the
// footprint is under a texel (lod <= 0), `min` and `mip` where it is larger (mip None: level 0).
struct TextureWrap {
  scene::Wrap s = scene::Wrap::Repeat;
  scene::Wrap t = scene::Wrap::Repeat;
  scene::Filter mag = scene::Filter::Linear;
  scene::Filter min = scene::Filter::Linear;
  scene::MipFilter mip = scene::MipFilter::Linear;
};

class MipTexture {
 public:
  // Builds levels 1..n by 2×2 box filtering (odd sizes clamp at the edge). Level 0 points at
  // texture.rgba8, which must outlive this object (the Tracer's scene does).
  explicit MipTexture(const scene::Texture& texture);
  explicit MipTexture(scene::Texture&&) = delete;  // level 0 would dangle

  int levels() const { return static_cast<int>(levels_.size()); }
  int width(int level = 0) const { return levels_[static_cast<std::size_t>(level)].width; }
  int height(int level = 0) const { return levels_[static_cast<std::size_t>(level)].height; }

  using Wrap = TextureWrap;

  // Filtered lookup as a GPU sampler does it: lod <= 0 is magnification (wrap.mag at level 0);
  // above, wrap.min within a level and wrap.mip between levels (Linear: the two levels around
  // lod, blended; Nearest: the level nearest lod; None: level 0). The defaults are trilinear.
  // lod is clamped to [0, levels-1]. srgb: decode colour channels from sRGB first (alpha stays
  // linear).
  glm::vec4 sample(glm::vec2 uv, float lod, bool srgb, Wrap wrap = {}) const;
  // One level, bilinear (or the nearest texel with filter Nearest).
  glm::vec4 sample_level(glm::vec2 uv, int level, bool srgb, Wrap wrap = {},
                         scene::Filter filter = scene::Filter::Linear) const;
  // One texel of one level, unfiltered; x and y are addressed by `wrap`.
  glm::vec4 texel(int level, int x, int y, bool srgb, Wrap wrap = {}) const;

  // Mip level for a ray-cone footprint: the footprint is `width` metres across (at normal
  // incidence), seen at |cos| = cos_theta, on a triangle whose UV area is uv_area for world area
  // world_area. One texel per footprint width is level 0; every doubling adds one level.
  float lod_for_footprint(float width, float cos_theta, float uv_area, float world_area) const;
  // The same in two steps, so a hit computes the texture-independent part once for all its
  // textures: footprint_log2() is log2 of the footprint in UV units (-inf when there is none).
  static float footprint_log2(float width, float cos_theta, float uv_area, float world_area);
  float lod_for_footprint_log2(float log2_uv_footprint) const {
    return std::max(0.0f, log2_uv_footprint + half_log2_texels_);
  }

 private:
  struct Level {
    int width = 0;
    int height = 0;
    const std::uint8_t* data = nullptr;  // width * height * 4
  };
  std::vector<Level> levels_;
  std::vector<std::vector<std::uint8_t>> storage_;  // levels 1..n
  float half_log2_texels_ = 0.0f;                   // log2 of sqrt(texels at level 0)
};

// A material slot's addressing.
inline TextureWrap wrap_of(const scene::TextureSlot& slot) {
  return {slot.wrap_s, slot.wrap_t, slot.mag_filter, slot.min_filter, slot.mip_filter};
}

// sRGB transfer function (IEC 61966-2-1), 8-bit code → linear, by table.
float srgb_to_linear(std::uint8_t code);

// Every texture of a scene, mip-mapped once (in parallel) when the tracer is built.
class TextureSet {
 public:
  explicit TextureSet(const scene::Scene& scene);
  const MipTexture* get(int index) const {
    return index >= 0 && static_cast<std::size_t>(index) < textures_.size()
               ? &textures_[static_cast<std::size_t>(index)]
               : nullptr;
  }
  std::size_t size() const { return textures_.size(); }

 private:
  std::vector<MipTexture> textures_;
};

}  // namespace ddish::trace
