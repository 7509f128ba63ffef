// Mip chains of glTF metallic-roughness textures, built on the CPU with the roughness channel (G)
// averaged as a power mean instead of linearly.
//
// Why: a pixel that covers many texels should shade like the mean of the texels' shading, which
// is what the path tracer's pixel converges to. Roughness enters the BRDF non-linearly, so the
// linear mean of the roughness does not shade like that: on Sponza's floor
// (sponza_floor_a_rough.png) the brightness is concave in roughness toward grazing view, so
// shading the linear mean overshoots the path tracer (docs/materials.md has the figures). A
// power mean M_p = (mean r^p)^(1/p) with p < 1 lies below the linear mean (p > 1 above it, p = 2
// is averaging GGX's alpha = r^2); p is chosen by measurement against the path tracer.
// R (occlusion when packed), B (metallic) and A are averaged linearly, as the GPU's blits do.
#pragma once

#include <cstdint>
#include <vector>

#include "scene/scene.h"

namespace ddish::raster {

// The power of the roughness mean (see above), measured on the report's cameras.
inline constexpr float kRoughnessMipPower = 0.5f;

struct MipLevel {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::vector<std::uint8_t> rgba8;  // width * height * 4 bytes
};

// The texture's whole chain, level 0 first (its texels unchanged), down to 1 x 1: each level
// halves each side (rounding down, at least 1) and each texel is the mean of the 2 x 2 texels
// above it (a side of 1, or an odd side's last row or column, reuses the texels it has). The
// roughness of a level is the power mean of the level-0 texels it covers, kept in full precision
// down the chain and rounded to 8 bits per level. Throws std::invalid_argument for power <= 0
// or for a texture whose rgba8 is not width * height * 4 bytes.
std::vector<MipLevel> roughness_mip_chain(const scene::Texture& texture, float power);

}  // namespace ddish::raster
