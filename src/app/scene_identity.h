// The scene identity of the probe stream (docs/protocol.md): a 64-bit FNV-1a hash of the scene's
// geometry as loaded (every mesh's positions and triangles, every node's rest transform and
// meshes) and of the probe grid (counts, bounds) and SH order. A server and a client agree on
// it only when they load the same geometry and place the same probes, so a client of another
// scene or grid is refused before anything of it is drawn. The geometry's part is taken before
// the scene is posed (posing moves animated nodes), so every --time gives the same identity.
#pragma once

#include <cstdint>

#include "probes/probe_grid.h"

namespace ddish::scene {
struct Scene;
}

namespace ddish::app {

// Of the scene as loaded: call before Scene::pose.
std::uint64_t geometry_identity(const scene::Scene& scene);
std::uint64_t scene_identity(std::uint64_t geometry, const probes::ProbeGrid& grid, int sh_order);

}  // namespace ddish::app
