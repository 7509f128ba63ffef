#include "app/probe_options.h"

#include <chrono>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "probes/grid_placement.h"
#include "scene/scene.h"
#include "trace/tracer.h"

namespace ddish::app {

void add_probe_options(CLI::App& cmd, ProbeArgs& a) {
  cmd.add_option("--grid", a.grid,
                 "probe counts X,Y,Z, or auto (default: sidecar counts, else automatic)");
  cmd.add_option("--probe-spacing", a.spacing, "fit the grid to the bounds at this spacing (m)");
  cmd.add_option("--probe-placement", a.placement,
                 "centres: probes at the cell centres of the grid over the bounds; fit: the grid "
                 "moved by a quarter cell on an axis where the surfaces the scene's cameras see "
                 "then see more of their probes (a server's clients must ask for the same)")
      ->check(CLI::IsMember({"centres", "fit"}))
      ->capture_default_str();
  cmd.add_option("--probe-samples", a.samples, "paths per probe per update")->capture_default_str();
  cmd.add_option("--bounces", a.bounces,
                 "scattering events per probe path, the probe ray's first hit counting as one: 0 "
                 "only emitters and sky seen directly, 1 direct light at the first hit, 2 one "
                 "indirect bounce more, ...")
      ->capture_default_str();
  cmd.add_option("--hysteresis", a.hysteresis, "running-average hysteresis in [0, 1)")
      ->capture_default_str();
  cmd.add_option("--sh-order", a.sh_order, "SH order 1..4")->capture_default_str();
  cmd.add_option("--seed", a.seed, "random seed")->capture_default_str();
}

void add_visibility_options(CLI::App& cmd, ProbeArgs& a) {
  cmd.add_option("--probe-visibility", a.visibility,
                 "R: an R x R octahedral map of distance moments per probe, gathered from the "
                 "probe rays, for visibility-aware interpolation (no light through walls); 0: off")
      ->capture_default_str();
  cmd.add_flag("--probe-relocation", a.relocate,
               "move a probe found inside geometry, or nearer than a tenth of a cell to a surface, "
               "within 0.45 of its cell before classifying it (the probe traces again from there "
               "once)");
}

probes::ProbeVolume local_volume(const ProbeArgs& a, const probes::ProbeGrid& grid) {
  return probes::ProbeVolume(grid, a.sh_order, a.visibility);
}

glm::ivec3 parse_grid(const std::string& text) {
  std::stringstream ss(text);
  glm::ivec3 c(0);
  char comma1 = 0, comma2 = 0;
  ss >> c.x >> comma1 >> c.y >> comma2 >> c.z;
  if (!ss || comma1 != ',' || comma2 != ',' || ss.peek() != std::char_traits<char>::eof())
    throw std::invalid_argument("--grid expects three counts X,Y,Z or auto, got '" + text + "'");
  if (c.x < 1 || c.y < 1 || c.z < 1)
    throw std::invalid_argument("--grid counts must be at least 1 on every axis, got '" + text +
                                "'");
  return c;
}

void check_probe_options(const ProbeArgs& a) {
  const bool counts = !a.grid.empty() && a.grid != "auto";
  if (!a.grid.empty() && a.spacing)
    throw std::invalid_argument("give either --grid or --probe-spacing, not both");
  if (counts) parse_grid(a.grid);
  if (a.spacing && !(*a.spacing > 0.0f))
    throw std::invalid_argument(fmt::format("--probe-spacing must be positive, got {:g}", *a.spacing));
  if (a.samples < 1) throw std::invalid_argument("--probe-samples must be at least 1");
  if (a.bounces < 0) throw std::invalid_argument("--bounces must be 0 or more");
  if (!(a.hysteresis >= 0.0f && a.hysteresis < 1.0f))
    throw std::invalid_argument(fmt::format("--hysteresis must be in [0, 1), got {:g}", a.hysteresis));
  if (a.visibility < 0 || a.visibility > probes::kMaxMomentResolution)
    throw std::invalid_argument(fmt::format("--probe-visibility must be 0 (off) .. {}, got {}",
                                            probes::kMaxMomentResolution, a.visibility));
  if (a.sh_order < 1 || a.sh_order > 4)
    throw std::invalid_argument(fmt::format("--sh-order must be 1, 2, 3 or 4, got {}", a.sh_order));
}

namespace {

Placement place_over_bounds(const ProbeArgs& a, const scene::Scene& s) {
  const bool sidecar_bounds = s.sidecar.probe_bounds.has_value();
  const scene::Aabb bounds = sidecar_bounds ? *s.sidecar.probe_bounds : s.bounds();
  if (bounds.empty() && s.triangle_count() == 0)  // points and lines only, or no meshes at all
    throw std::invalid_argument(s.path + ": the scene has no triangles to draw (points and lines "
                                "are not drawn; ddish info lists what the loader skipped)");
  if (bounds.empty())
    throw std::invalid_argument(s.path + ": the scene has no geometry to fit a probe grid to "
                                "(give probe_bounds in its sidecar)");
  const std::string over = sidecar_bounds ? "sidecar bounds" : "scene bounds";
  if (!a.grid.empty() && a.grid != "auto")
    return {probes::ProbeGrid(bounds, parse_grid(a.grid)), "--grid over " + over};
  if (a.spacing)
    return {probes::ProbeGrid::fit_spacing(bounds, *a.spacing),
            fmt::format("--probe-spacing {:g} m over {}", *a.spacing, over)};
  if (s.sidecar.probe_counts && a.grid != "auto")
    return {probes::ProbeGrid(bounds, *s.sidecar.probe_counts), "sidecar counts over " + over};
  // Sidecar bounds are where the probes are wanted (a room); the scene's own bounds may be an
  // object in open space, which needs probes around it (ProbeGrid::fit_auto_around).
  if (sidecar_bounds)
    return {probes::ProbeGrid::fit_auto(bounds),
            fmt::format("automatic ({} along the longest axis) over {}",
                        probes::ProbeGrid::kAutoLongestAxisProbes, over)};
  return {probes::ProbeGrid::fit_auto_around(bounds),
          fmt::format("automatic ({} along the longest axis) over the scene bounds and a "
                      "{}-cell margin",
                      probes::ProbeGrid::kAutoLongestAxisProbes,
                      probes::ProbeGrid::kAutoMarginCells)};
}

// Bounces of the paths that look for light at the surface points: a gallery behind an arcade
// is reached by light after two or three.
constexpr int kPlacementBounces = 4;

// The grid moved to where its probes see the most of the surfaces (probes/grid_placement.h),
// traced with a tracer of its own: the probe tracer is built later, and may be the GPU's.
Placement fitted(Placement p, const scene::Scene& s) {
  const auto start = std::chrono::steady_clock::now();
  trace::PathOptions paths;
  paths.max_bounces = kPlacementBounces;
  const trace::Tracer tracer(s, paths);
  const probes::GridFit fit = probes::fit_grid_placement(p.grid, s, tracer);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const glm::vec3 o = fit.offset_cells;
  std::fprintf(stderr,
               "probe placement: fit over %u surface points, %u grids in %.1f s: moved (%g, %g, %g) "
               "cells, surfaces see %.1f %% of their probes' weight (%.1f %% at the cell centres)\n",
               fit.points, fit.grids_scored, seconds, o.x, o.y, o.z, 100.0 * fit.score,
               100.0 * fit.unmoved_score);
  p.grid = fit.grid;
  p.how += fmt::format(", moved ({:g}, {:g}, {:g}) cells by --probe-placement fit", o.x, o.y, o.z);
  return p;
}

}  // namespace

Placement place_probes(const ProbeArgs& a, const scene::Scene& s) {
  Placement p = place_over_bounds(a, s);
  return a.placement == "fit" ? fitted(std::move(p), s) : p;
}

probes::UpdateOptions update_options(const ProbeArgs& a) {
  probes::UpdateOptions options;
  options.samples = static_cast<std::uint32_t>(a.samples);
  options.hysteresis = a.hysteresis;
  options.seed = a.seed;
  options.relocate = a.relocate;
  return options;
}

}  // namespace ddish::app
