// What the tracing benchmarks (trace_floor, trace_vk_rate) share: the probe grid they trace and
// the median of repeated timings, so that their figures are of the same probes.
#pragma once

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "probes/probe_grid.h"
#include "scene/scene.h"

namespace ddish::bench {

// --grid X,Y,Z over the sidecar's probe bounds (else the scene's bounds); without it the
// sidecar's counts, else the automatic grid over those bounds.
inline probes::ProbeGrid place_grid(const scene::Scene& s, const std::string& grid) {
  const scene::Aabb bounds = s.sidecar.probe_bounds ? *s.sidecar.probe_bounds : s.bounds();
  if (!grid.empty()) {
    glm::ivec3 c{0};
    if (std::sscanf(grid.c_str(), "%d,%d,%d", &c.x, &c.y, &c.z) != 3 || c.x < 1 || c.y < 1 || c.z < 1)
      throw std::invalid_argument("--grid needs three positive counts X,Y,Z, got '" + grid + "'");
    return probes::ProbeGrid(bounds, c);
  }
  if (s.sidecar.probe_counts) return probes::ProbeGrid(bounds, *s.sidecar.probe_counts);
  return probes::ProbeGrid::fit_auto(bounds);
}

inline double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace ddish::bench
