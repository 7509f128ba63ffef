// The probe options that `ddish probes` and `ddish render` (and later the server) share:
// placement (--grid X,Y,Z|auto, --probe-spacing M), the update (--probe-samples, --bounces,
// --hysteresis, --seed) and --sh-order, with their checks and the grid they place.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "probes/probe_grid.h"
#include "probes/probe_tracer.h"
#include "probes/probe_volume.h"

namespace CLI {
class App;
}

namespace ddish::scene {
struct Scene;
}

namespace ddish::app {

// Probe paths scatter at most this many times by default: one fewer than `ddish reference`'s 16
// bounces, because the rasterized surface is the first scattering of the light a probe
// delivers, so a view and its reference carry the same light transport. Shorter paths are a
// bias, not noise: in the Breakfast room (white walls, albedo 0.9) 4 probe bounces left every
// surface off the sunlit patches 33 % too dark (19.9 dB against the reference, 23.6 dB with 16)
// for 1.47x the rays; in Sponza, where paths escape to the sky, the rays grew 0.3 %. Russian
// roulette (from the 3rd bounce) ends most long paths early.
inline constexpr int kDefaultProbeBounces = 15;

// --probe-visibility: R of the R x R distance-moment map per probe (probes/moment_map.h), 0 to
// interpolate without visibility. docs/probe-visibility.md has the measurements behind it.
inline constexpr int kDefaultProbeVisibility = 8;

struct ProbeArgs {
  std::string grid;  // "X,Y,Z", "auto", or empty (sidecar counts, else automatic)
  std::optional<float> spacing;
  int samples = 256;
  int bounces = kDefaultProbeBounces;
  float hysteresis = probes::kDefaultHysteresis;
  int sh_order = probes::kDefaultShOrder;
  std::uint64_t seed = 1;
  int visibility = kDefaultProbeVisibility;  // moment map resolution; 0: no visibility
  bool relocate = false;                     // --probe-relocation
  std::string placement = "centres";         // --probe-placement: centres | fit
};

// Registers --grid, --probe-spacing, --probe-placement, --probe-samples, --bounces, --hysteresis,
// --sh-order and --seed on cmd, writing into args (which must outlive the parse).
void add_probe_options(CLI::App& cmd, ProbeArgs& args);
// Registers --probe-visibility and --probe-relocation, for the commands that trace a volume in
// process and rasterize or write it.
void add_visibility_options(CLI::App& cmd, ProbeArgs& args);

// Throws std::invalid_argument with a one-line message for an impossible combination or value.
void check_probe_options(const ProbeArgs& args);

// The volume an in-process probe update fills, with moment maps of --probe-visibility (both
// tracers gather them from their probe rays).
probes::ProbeVolume local_volume(const ProbeArgs& args, const probes::ProbeGrid& grid);

// "X,Y,Z" -> three positive counts; throws std::invalid_argument otherwise.
glm::ivec3 parse_grid(const std::string& text);

struct Placement {
  probes::ProbeGrid grid;
  std::string how;  // e.g. "--grid over sidecar bounds", for the command's report
};

// --grid counts or --probe-spacing over the sidecar's probe_bounds (else the scene's bounds);
// without either, the sidecar's probe counts; without those (or with --grid auto), automatic:
// over the sidecar's bounds as they are, over the scene's with a margin (fit_auto_around).
// With --probe-placement fit the grid is then moved by a fraction of a cell to where its probes
// see the most of the surfaces they light (probes/grid_placement.h); this traces the scene
// (about a second for Sponza) and reports on stderr.
Placement place_probes(const ProbeArgs& args, const scene::Scene& scene);

probes::UpdateOptions update_options(const ProbeArgs& args);

}  // namespace ddish::app
