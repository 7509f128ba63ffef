// What the forward pass's fragment stage computes (RendererOptions::shading):
//   full     the renderer's shading (forward_main.glsl: direct light, SH probes, emission);
//   trivial  a constant colour (forward_trivial.frag writes kTrivialColor), same vertex shader,
//            geometry, depth test, MSAA, passes and target: the vertex + raster + fill floor that
//            a view's full cost is compared against (bench/raster_views --shading trivial, the
//            results' "trivial-shader floor"). It samples no texture, so alpha-masked materials
//            are drawn solid (a few more fragments than full shading keeps).
#pragma once

#include <optional>
#include <string_view>

#include <glm/glm.hpp>

namespace ddish::raster {

enum class Shading { full, trivial };

// The linear radiance forward_trivial.frag writes (exact in the RGBA16F target); keep in step.
inline constexpr glm::vec3 kTrivialColor{0.5f, 0.25f, 0.125f};

std::string_view to_string(Shading s);
std::optional<Shading> parse_shading(std::string_view name);

}  // namespace ddish::raster
