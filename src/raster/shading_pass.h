// How the full shading reaches the pixels (RendererOptions::shading_pass):
//   forward     the forward pass (raster/forward_pass.h): each triangle's fragments are shaded
//               as it is drawn (after a depth prepass where the device has one);
//   visibility  the visibility pass (raster/visibility_pass.h): one geometry pass writes the
//               instance and triangle of every sample, then one full-screen pass per view
//               shades each pixel once, from the triangles its samples hold.
// Both give the same image (tests/raster/visibility_pass_test.cpp). On lavapipe, which shades
// 4x4 pixel blocks, the visibility pass spends its lanes on visible pixels only: measured in
// visibility_pass.h.
#pragma once

#include <optional>
#include <string_view>

namespace ddish::raster {

enum class ShadingPass { forward, visibility };

std::string_view to_string(ShadingPass p);
std::optional<ShadingPass> parse_shading_pass(std::string_view name);

}  // namespace ddish::raster
