// Fitted grid placement (`--probe-placement fit`): the whole probe grid moved by a fraction of a
// cell so that its probes see the surfaces they light.
//
// A regular grid is blind to the architecture: on Sponza's half grid (8 × 4 × 4) the four rows
// across the building fall two in the closed cavities outside its walls and two under the
// arcades, none in the courtyard, and the galleries render black (17.2 dB against 22.6 for the
// full grid, CameraMain); moved a quarter cell on each axis it scores 20.1 dB. Which offset is
// right follows from what interpolation needs: a surface point reads the 8 probes at its
// cell's corners, and a probe it cannot see gives it the light of another room (or none, if
// visibility weights it out). So each candidate grid is scored by the mean, over surface
// points, of the trilinear weight that falls on probes the point sees (an unoccluded segment
// from just above the surface to the probe), and the best offset is kept.
//
// The points are those the scene's cameras see (first hits of rays through their fields of
// view, all cameras alike): the surfaces someone looks at. Points sampled by area over every
// surface score the outside of Sponza's roof and shell as much as its courtyard, and a fit to
// them (half-cell offsets allowed, 4 frames) lost 2.2 dB from CameraMain; a scene without cameras falls back to them, less the ones no
// light reaches (lit_surfaces). The result depends on the scene file only (fixed seed, per-task
// sums added in order), so a server and its clients that both ask for it agree, and the scene
// identity (app/scene_identity.h) covers the moved bounds if they do not.
//
// Candidates: 0 and ±1/4 of a cell on each axis, one axis after the other (coordinate descent,
// 7 grids), every grid scored on the same points so that their differences are not sampling
// noise. Not 1/2: that puts a layer of probes on the bounds, which are usually walls, floors
// and ceilings (ProbeGrid's comment): with it the Breakfast room's probes rose half a cell to
// its ceiling and its default camera lost 1.0 dB, while with ±1/4 it gains 0.1. An offset is
// taken only when it beats the one kept by kPlacementMinGain, so a grid that is already as good
// stays where the scene's bounds put it. Measured gains and losses per camera are in
// docs/probe-visibility.md. Two of Sponza's cameras lose a little, and a client on another
// machine could, in a near tie, fit another offset than its server (the identity then refuses
// it), so it is asked for, not the default.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "probes/probe_grid.h"

namespace ddish::scene {
struct Scene;
}
namespace ddish::trace {
class EmbreeScene;
class Tracer;
}

namespace ddish::probes {

inline constexpr std::uint32_t kPlacementSurfacePoints = 16384;
inline constexpr std::uint64_t kPlacementSeed = 1;
// Points are lifted this many of the smallest cell along their normal before they look.
inline constexpr float kPlacementLiftCells = 0.01f;
// Paths per surface point that look for light (lit_surfaces).
inline constexpr std::uint32_t kPlacementLightPaths = 8;
// Offsets tried on each axis, in cells; 0 first, so that ties keep the bounds' placement.
inline constexpr float kPlacementOffsets[] = {0.0f, 0.25f, -0.25f};
// Smallest gain in score (a fraction of the interpolation weight) worth moving the grid for:
// ten times the sampling noise of a difference between two grids on the same 16384 points.
inline constexpr double kPlacementMinGain = 0.01;

// A point on a surface and the unit normal of the side that is seen (both sides of a
// double-sided material, each with half the points).
struct SurfaceSample {
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f, 0.0f, 1.0f};
};

// `count` points uniform by area over the scene's triangles (degenerate ones skipped) with a
// fixed seed. Empty when the scene has no triangle of positive area.
std::vector<SurfaceSample> sample_surfaces(const scene::Scene& scene, std::uint32_t count,
                                           std::uint64_t seed = kPlacementSeed);

// The points that any light reaches: those from which one of `paths` cosine-distributed paths
// (the tracer's bounces, from `lift` metres above the surface) carries radiance. A surface in a
// closed, unlit cavity (Sponza's space between its walls and its outer shell) is black whichever
// probe lights it, so where the probes fall does not matter to it, and it is not scored.
std::vector<SurfaceSample> lit_surfaces(std::span<const SurfaceSample> points, const trace::Tracer& tracer,
                                        float lift, std::uint32_t paths = kPlacementLightPaths);

// True when nothing blocks the segment from `from` to `to`.
using SegmentVisible = std::function<bool(const glm::vec3& from, const glm::vec3& to)>;

// The mean over `points` of the trilinear weight on the probes of `grid` that each point sees
// from just above its surface (kPlacementLiftCells of the smallest cell along its normal); positions
// outside the grid are clamped to it, as the shader does. 0 for no points.
double visible_weight(const ProbeGrid& grid, std::span<const SurfaceSample> points,
                      const SegmentVisible& visible);

// `grid` moved by `offset_cells` cells per axis (its counts and spacing kept).
ProbeGrid shifted_grid(const ProbeGrid& grid, const glm::vec3& offset_cells);

struct GridFit {
  ProbeGrid grid;                      // the chosen grid
  glm::vec3 offset_cells{0.0f};        // how far it moved from the input's placement
  double score = 0.0;                  // visible_weight of the chosen grid
  double unmoved_score = 0.0;          // visible_weight of the input grid
  std::uint32_t grids_scored = 0;
  std::uint32_t points = 0;
};

// Coordinate descent over kPlacementOffsets (see above). With no surface points the input grid
// is returned unmoved.
GridFit fit_grid_placement(const ProbeGrid& grid, std::span<const SurfaceSample> points,
                           const SegmentVisible& visible);

// The points the scene's cameras see: `count` rays, camera k % cameras, uniform over each
// camera's image plane (its aspect, else 4:3), their first hits with the normal turned toward
// the camera. Misses are dropped; empty when the scene has no camera.
std::vector<SurfaceSample> camera_surfaces(const scene::Scene& scene, const trace::EmbreeScene& embree,
                                           std::uint32_t count, std::uint64_t seed = kPlacementSeed);

// The same over the surface points the scene's cameras see (camera_surfaces), else over its lit
// surface points (sample_surfaces, then lit_surfaces); the segments traced in the tracer's
// Embree scene, in parallel.
GridFit fit_grid_placement(const ProbeGrid& grid, const scene::Scene& scene, const trace::Tracer& tracer);

}  // namespace ddish::probes
