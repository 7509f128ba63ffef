// Classification, second phase: probes with nothing to light are left out.
//
// The rasterizer lights a surface point with the 8 probes at the corners of the grid cell it lies
// in (positions outside the grid are clamped to it). A probe whose up to 8 neighbouring cells hold
// no surface is therefore read by no pixel of any view: tracing it is wasted work, and sending it
// wasted bandwidth. Such probes (the air in the middle of an atrium, the space around an object
// in the open) are made inactive before the first update, never traced, never uploaded or sent.
//
// What counts as "holds a surface" is conservative: a cell is marked when a triangle overlaps it
// grown by kSurfaceMarginCells on every side (exact triangle-box test), so that a shading point
// nudged along its normal or towards the viewer (visibility-aware interpolation biases of up to a
// fraction of a cell) still finds its probes. Triangles that leave the grid mark every cell of
// their bounding box clamped to the grid, as the shader's clamp maps their outside points onto
// the border cells. Instances that move (node animation) mark the cells their bounds sweep over
// the whole animation, sampled at kAnimationSamples times, each pair of samples joined.
#pragma once

#include <cstdint>
#include <vector>

#include "probes/probe_grid.h"
#include "probes/probe_volume.h"

namespace ddish::scene {
struct Scene;
}

namespace ddish::probes {

inline constexpr float kSurfaceMarginCells = 0.5f;
inline constexpr int kAnimationSamples = 64;

// For every probe of `grid` (grid index order): true when a surface of the scene lies in one of
// its neighbouring cells at some time of the scene's animation. Poses the scene at sampled
// times when it is animated, and back at its current time before returning.
std::vector<bool> probes_near_surfaces(const ProbeGrid& grid, scene::Scene& scene);

// The triangle (a, b, c) overlaps the axis-aligned box [lo, hi] (separating-axis test: the
// box's 3 axes, the triangle's normal and the 9 edge-axis cross products). Touching counts.
bool triangle_overlaps_box(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
                           const glm::vec3& lo, const glm::vec3& hi);

// Makes every probe that `near_surface` says false for inactive (not inside geometry), zeroed
// like any inactive probe. Returns how many were left out.
std::uint32_t leave_out_probes(ProbeVolume& volume, const std::vector<bool>& near_surface);

}  // namespace ddish::probes
