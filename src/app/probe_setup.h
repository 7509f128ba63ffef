// The probe seam as the commands build it from their options, shared by `render`, `view` and
// `xr`: the in-process parts (path tracer, probe tracer, scheduler) or the probe stream's client
// (app/remote_probes.h) with its starting volume.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "app/probe_options.h"
#include "app/probe_source.h"
#include "app/schedule_options.h"
#include "app/tracer_choice.h"
#include "net/probe_client.h"
#include "probes/probe_tracer.h"
#include "probes/probe_volume.h"
#include "probes/scheduler.h"
#include "scene/features.h"
#include "trace/tracer.h"

namespace ddish::app {

// `--connect` and its companions (ddish view, ddish xr --connect).
struct StreamArgs {
  std::string connect;   // empty: in-process probes; several servers: comma-separated
  std::string baked;     // --probes FILE: the probes until a server answers
  int wait_ms = 2000;    // frame 0's wait for the server's snapshot
  int stale_ms = 1000;   // no message for this long while connected: the server is slow
  int frame_wait_ms = 0;  // later frames' wait for the server's next frame
  std::string curve_server_key;  // the server's .pub
  std::string curve_secret;      // this client's .key
  std::string relay;             // the frames through a ddish relay; empty: from each server
  // What the servers said of their stream at start (describe_stream); none: no answer.
  std::optional<net::StreamDescription> described;
};

// The in-process probe half: the probe tracer (--tracer's choice) and the scheduler.
struct InProcessParts {
  ProbeEngine engine;
  probes::Scheduler scheduler;
  double budget_ms;
  InProcessParts(const ProbeArgs& probe, const ScheduleArgs& schedule, const scene::Scene& s,
                 const trace::PathOptions& path, double budget, TracerKind tracer,
                 std::optional<std::uint32_t> device, const gpu::Device* shared);
};

// The in-process parts for `probe` and `schedule` with a frame budget (0: none), tracing with
// `tracer` (for TracerKind::vulkan on `shared`, a device opened with ray tracing, else on a
// context of its own on Vulkan device `device`).
std::unique_ptr<InProcessParts> make_in_process(const ProbeArgs& probe, const ScheduleArgs& schedule,
                                                const scene::Scene& s, double budget_ms, TracerKind tracer,
                                                std::optional<std::uint32_t> device,
                                                const gpu::Device* shared = nullptr);

// Classification's second phase for an in-process volume: the probes with no surface near them
// are left out before the first update (probes/surface_cells.h). Returns how many.
std::uint32_t leave_out_empty_probes(probes::ProbeVolume& volume, scene::Scene& s);

// What `ddish info` and the run logs list of them among what is left out:
// "N of the grid's M probes (X x Y x Z): no surface within half a cell of ...".
scene::PlanItem empty_probes_item(std::uint32_t left_out, const probes::ProbeGrid& grid);

// Asks the servers of stream.connect for their stream's description (up to stream.wait_ms) into
// stream.described, and says on stderr what the stream carries. --wait-ms bounds this wait and
// the first frame's together: the time the description took comes off stream.wait_ms, which is
// what the first frame then waits for the snapshot (make_probe_source), so a client with no
// server answering waits --wait-ms once, not twice. Call after the options are checked.
void describe_stream(StreamArgs& stream, const char* tag);

// A stream client's probe grid: where the servers described their grid and its counts are those
// this client places (--grid, the sidecar's, automatic), the servers' bounds, so a grid that
// `serve --probe-placement fit` moved is the client's without a fit of its own (one line on
// stderr says by how much it moved); otherwise place_probes, and a server of another grid is
// refused by the scene identity.
Placement client_placement(const ProbeArgs& probe, const scene::Scene& s, const StreamArgs& stream,
                           const char* tag);

// The stream client's starting probes: the --probes volume (same grid and order as the
// placement, or an error), else none (direct light only until a server answers). Its moment
// maps are the ones stream.described announces, so that the renderer sizes its visibility data
// for what the stream carries; without a description, the baked volume's, else
// --probe-visibility's (8 by default, serve's default; one line on stderr says which), and a
// server of other maps is refused with a line that says so.
probes::ProbeVolume starting_volume(const ProbeArgs& probe, const StreamArgs& stream,
                                    const Placement& placement, const char* tag);

// The frame loop's probe source: in-process over `local`, else the stream's client (`tag` names
// the command in its log lines). Everything is borrowed.
std::unique_ptr<ProbeSource> make_probe_source(InProcessParts* local, const ProbeArgs& probe,
                                               const ScheduleArgs& schedule, const StreamArgs& stream,
                                               probes::ProbeVolume& volume, std::uint64_t identity,
                                               const char* tag);

}  // namespace ddish::app
