#include "app/probe_setup.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <optional>
#include <stdexcept>

#include <fmt/format.h>

#include "app/remote_probes.h"
#include "net/curve_keys.h"
#include "net/probe_client.h"
#include "probes/surface_cells.h"
#include "probes/volume_file.h"

namespace ddish::app {

InProcessParts::InProcessParts(const ProbeArgs& probe, const ScheduleArgs& schedule, const scene::Scene& s,
                               const trace::PathOptions& path, double budget, TracerKind tracer,
                               std::optional<std::uint32_t> device, const gpu::Device* shared)
    : engine(tracer, s, path, update_options(probe), device, shared),
      scheduler(scheduler_options(schedule, probe, budget)),
      budget_ms(budget) {}

std::unique_ptr<InProcessParts> make_in_process(const ProbeArgs& probe, const ScheduleArgs& schedule,
                                                const scene::Scene& s, double budget_ms, TracerKind tracer,
                                                std::optional<std::uint32_t> device, const gpu::Device* shared) {
  trace::PathOptions path_options;
  path_options.max_bounces = probe.bounces;
  return std::make_unique<InProcessParts>(probe, schedule, s, path_options, budget_ms, tracer, device, shared);
}

std::uint32_t leave_out_empty_probes(probes::ProbeVolume& volume, scene::Scene& s) {
  return probes::leave_out_probes(volume, probes::probes_near_surfaces(volume.grid(), s));
}

scene::PlanItem empty_probes_item(std::uint32_t left_out, const probes::ProbeGrid& grid) {
  const glm::ivec3 c = grid.counts();
  return {fmt::format("{} of the grid's {} probes ({} x {} x {})", left_out, grid.probe_count(), c.x, c.y, c.z),
          "no surface within half a cell of the cells they light: never traced, uploaded or sent"};
}

namespace {

net::ClientOptions client_options(const StreamArgs& stream, const char* tag) {
  net::ClientOptions co;
  co.connect = stream.connect;
  co.stale_ms = stream.stale_ms;
  co.relay = stream.relay;
  const std::string prefix = tag;
  co.log = [prefix](const std::string& line) { std::fprintf(stderr, "%s: %s\n", prefix.c_str(), line.c_str()); };
  if (!stream.curve_secret.empty()) {
    const net::CurveKeyPair mine = net::read_secret_key(stream.curve_secret);
    co.curve = net::CurveClientKeys{net::read_public_key(stream.curve_server_key), mine.public_z85, mine.secret_z85};
  }
  return co;
}

}  // namespace

void describe_stream(StreamArgs& stream, const char* tag) {
  std::string problem;
  const auto asked = std::chrono::steady_clock::now();
  stream.described = net::ask_stream_description(client_options(stream, tag), stream.wait_ms, &problem);
  const auto waited = std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - asked);
  stream.wait_ms = std::max(0, stream.wait_ms - int(waited.count()));
  if (stream.described) {
    const int resolution = stream.described->header.moment_resolution;
    std::fprintf(stderr, "%s: the server streams %s\n", tag,
                 resolution > 0 ? fmt::format("{0}x{0} distance-moment maps per probe (visibility on)", resolution).c_str()
                                : "no distance moments (visibility off)");
  } else {
    std::fprintf(stderr, "%s: no stream description from %s (%s): this client places its own probes\n", tag,
                 stream.connect.c_str(), problem.c_str());
  }
}

Placement client_placement(const ProbeArgs& probe, const scene::Scene& s, const StreamArgs& stream,
                           const char* tag) {
  ProbeArgs centred = probe;
  centred.placement = "centres";
  Placement own = place_probes(centred, s);
  if (stream.described && stream.described->bounds) {
    const net::FrameHeader& h = stream.described->header;
    const glm::ivec3 counts(int(h.counts[0]), int(h.counts[1]), int(h.counts[2]));
    if (counts == own.grid.counts()) {
      Placement theirs{probes::ProbeGrid(*stream.described->bounds, counts), own.how + ", bounds from the server"};
      const glm::vec3 spacing = own.grid.spacing();
      const glm::vec3 moved = theirs.grid.bounds().min - own.grid.bounds().min;
      glm::vec3 cells(0.0f);
      for (int c = 0; c < 3; ++c) cells[c] = spacing[c] > 0.0f ? moved[c] / spacing[c] : 0.0f;
      std::fprintf(stderr, "%s: probe grid %dx%dx%d over the server's bounds (moved (%.3g, %.3g, %.3g) cells from this scene's centred grid)\n",
                   tag, counts.x, counts.y, counts.z, double(cells.x), double(cells.y), double(cells.z));
      return theirs;
    }
  }
  return probe.placement == "fit" ? place_probes(probe, s) : own;
}

probes::ProbeVolume starting_volume(const ProbeArgs& probe, const StreamArgs& stream,
                                    const Placement& placement, const char* tag) {
  std::optional<probes::ProbeVolume> baked;
  if (!stream.baked.empty()) {
    baked = probes::read_volume_file(stream.baked).to_volume();
    if (baked->grid().counts() != placement.grid.counts() || baked->sh_order() != probe.sh_order)
      throw std::invalid_argument(fmt::format(
          "--probes {}: grid {}x{}x{} L{}, but this scene's probes are {}x{}x{} L{} (same --grid and --sh-order as the server)",
          stream.baked, baked->grid().counts().x, baked->grid().counts().y, baked->grid().counts().z,
          baked->sh_order(), placement.grid.counts().x, placement.grid.counts().y,
          placement.grid.counts().z, probe.sh_order));
  }
  const int resolution = stream.described ? stream.described->header.moment_resolution
                         : baked         ? baked->moment_resolution()
                                         : probe.visibility;
  if (!stream.described)
    std::fprintf(stderr, "%s: assuming %s until a server answers\n", tag,
                 resolution > 0 ? fmt::format("{0}x{0} distance-moment maps", resolution).c_str() : "no distance moments");
  if (!baked) return probes::ProbeVolume(placement.grid, probe.sh_order, resolution);
  if (baked->moment_resolution() == resolution) return std::move(*baked);
  // The baked probes' light, without their moment maps (of another resolution than the
  // stream's): interpolated without visibility until the server's probes arrive.
  probes::ProbeVolume volume(placement.grid, probe.sh_order, resolution);
  for (std::uint32_t i = 0; i < volume.probe_count(); ++i) {
    volume.state(i) = baked->state(i);
    std::copy(baked->coefficients(i).begin(), baked->coefficients(i).end(), volume.coefficients(i).begin());
    volume.set_offset(i, baked->offset(i));
  }
  volume.set_frame(baked->frame());
  return volume;
}

std::unique_ptr<ProbeSource> make_probe_source(InProcessParts* local, const ProbeArgs& probe,
                                               const ScheduleArgs& schedule, const StreamArgs& stream,
                                               probes::ProbeVolume& volume, std::uint64_t identity,
                                               const char* tag) {
  if (local) {
    return std::make_unique<InProcessProbes>(
        local->engine, local->scheduler,
        [&probe, &schedule](const probes::FramePlan& plan) {
          return frame_update_options(schedule, probe, plan.samples, plan.hysteresis);
        },
        volume);
  }
  const net::ClientOptions co = client_options(stream, tag);
  auto remote = std::make_unique<RemoteProbes>(co, volume, identity, stream.wait_ms, stream.frame_wait_ms);
  std::fprintf(stderr, "%s: probes from %s (scene identity %016llx)\n", tag, stream.connect.c_str(),
               static_cast<unsigned long long>(identity));
  return remote;
}

}  // namespace ddish::app
