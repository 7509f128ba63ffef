// ddish probes SCENE [--grid X,Y,Z | --probe-spacing M] [--probe-samples N] [--bounces N]
//                    [--updates K] [--hysteresis A] [--sh-order 1..4] [--seed N] [--out PATH]
//                    [--sky R,G,B] [--tracer auto|embree|vulkan]
//
// Places a probe volume in the scene, runs K probe updates with the probe tracer (a line per
// update), and reports rays traced, Mrays/s, time, active and inactive probes and the packed
// encoding; with --out it writes the volume (probes/volume_file.h) and PATH.json beside it.
// Placement: --grid counts or --probe-spacing over the sidecar's probe_bounds (else the scene's
// bounds); without either, the sidecar's probe counts; without those, automatic placement.
#include <filesystem>
#include <chrono>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "app/commands.h"
#include "app/lighting_options.h"
#include "app/probe_options.h"
#include "app/probe_setup.h"
#include "app/tracer_choice.h"
#include "io/atomic_file.h"
#include "probes/probe_grid.h"
#include "probes/probe_tracer.h"
#include "probes/probe_volume.h"
#include "probes/volume_file.h"
#include "probes/volume_packing.h"
#include "scene/gltf_loader.h"
#include "scene/scene.h"

namespace ddish::app {
namespace {

struct ProbesArgs {
  std::string scene;
  ProbeArgs probe;  // placement, update and SH options shared with `ddish render`
  LightingArgs lighting;  // --sky
  int updates = 1;
  std::string out;
  std::string tracer = "auto";
};

void check(const ProbesArgs& a) {
  check_probe_options(a.probe);
  sky_radiance(a.lighting);
  if (a.updates < 1) throw std::invalid_argument("--updates must be at least 1");
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

int run_probes(const ProbesArgs& a) {
  check(a);  // before loading: a bad option should not cost a scene load
  if (!a.out.empty()) io::check_writable_file(a.out);  // nor an output that cannot be written
  auto t0 = std::chrono::steady_clock::now();
  scene::Scene s = scene::load_scene(a.scene);
  const double load_s = seconds_since(t0);
  const std::string environment = apply_lighting(s, a.lighting);
  Placement placement = place_probes(a.probe, s);
  const probes::ProbeGrid& grid = placement.grid;

  const TracerDecision decision = choose_tracer(a.tracer, std::nullopt);
  t0 = std::chrono::steady_clock::now();
  trace::PathOptions path_options;
  path_options.max_bounces = a.probe.bounces;
  ProbeEngine engine(decision.kind, s, path_options, update_options(a.probe), std::nullopt);
  const double build_s = seconds_since(t0);
  fmt::print("{}: {} triangles, loaded in {:.2f} s, tracer built in {:.2f} s\n", s.path,
             s.triangle_count(), load_s, build_s);
  fmt::print("tracer   {}\n", decision.why);
  fmt::print("{}\n", environment);
  fmt::print("probes   {} x {} x {} = {} ({}), spacing {:.3g} x {:.3g} x {:.3g} m, L{} SH\n",
             grid.counts().x, grid.counts().y, grid.counts().z, grid.probe_count(),
             placement.how, grid.spacing().x, grid.spacing().y, grid.spacing().z, a.probe.sh_order);

  probes::ProbeVolume volume = local_volume(a.probe, grid);
  const std::uint32_t left_out = leave_out_empty_probes(volume, s);
  const probes::ProbeUpdater& probe_tracer = engine.updater();

  std::uint64_t rays = 0, paths = 0, invalid = 0;
  double seconds = 0.0;
  for (int k = 1; k <= a.updates; ++k) {
    probes::UpdateStats u = probe_tracer.update_all(volume);
    rays += u.rays;
    paths += u.paths;
    invalid += u.invalid_samples;
    seconds += u.seconds;
    fmt::print("update {}/{}: {} probes, {} paths, {:.2f} M rays in {:.3f} s ({:.2f} Mrays/s){}\n",
               k, a.updates, u.probes_traced, u.paths, double(u.rays) * 1e-6, u.seconds,
               u.mrays_per_second(),
               u.newly_inactive ? fmt::format(", {} found inside geometry", u.newly_inactive)
                                : std::string());
  }

  probes::PackedVolume packed = probes::pack_volume(volume);
  fmt::print("rays     {} traced ({} paths, {:.2f} rays per path) in {:.3f} s: {:.2f} Mrays/s\n",
             rays, paths, paths ? double(rays) / double(paths) : 0.0, seconds,
             seconds > 0.0 ? double(rays) / seconds * 1e-6 : 0.0);
  fmt::print("active   {} of {} probes, inactive {} ({} inside geometry, {} left out: no surface near)\n",
             volume.active_count(), volume.probe_count(), volume.inactive_count(),
             volume.inside_geometry_count(), left_out);
  fmt::print("encoding {} ({} fp16, {} shared-exponent probes; {} bytes per probe, {} bytes)\n",
             probes::encoding_name(packed.encoding), packed.half_probes, packed.shared_exp_probes,
             packed.words_per_probe * 2u, packed.bytes());
  if (packed.overflowed_probes)
    fmt::print("warning: {} probes exceeded the packed range and were saturated\n",
               packed.overflowed_probes);
  if (invalid) fmt::print("warning: {} paths returned non-finite radiance and were dropped\n", invalid);
  if (!a.out.empty()) {
    probes::write_volume_file(a.out, volume, packed);
    fmt::print("written  {} ({} bytes) and {}.json\n", a.out,
               std::filesystem::file_size(a.out), a.out);
  }
  return 0;
}

Action make_probes(CLI::App& root) {
  auto a = std::make_shared<ProbesArgs>();
  CLI::App* cmd =
      root.add_subcommand("probes", "update a probe volume and write it (debugging, baking)");
  cmd->add_option("scene", a->scene, "glTF 2.0 scene (.gltf or .glb)")->required();
  add_probe_options(*cmd, a->probe);
  add_visibility_options(*cmd, a->probe);
  add_lighting_options(*cmd, a->lighting, /*exposure=*/false);
  cmd->add_option("--updates", a->updates, "probe updates to run")->capture_default_str();
  cmd->add_option("--out", a->out, "write the volume here (and a JSON summary at PATH.json)");
  add_tracer_option(*cmd, a->tracer);
  return [a]() { return run_probes(*a); };
}

}  // namespace

DDISH_COMMAND(30, make_probes);

}  // namespace ddish::app
