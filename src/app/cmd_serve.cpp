// ddish serve SCENE [--bind tcp://127.0.0.1:PORT] [--insecure] [--fps F] [--frames N]
//                   [--seconds S] [--time T] [--encoding fp16|shared-exponent|compact] [--zstd]
//                   [--delta-threshold R] [--delta-floor A] [--moment-threshold M]
//                   [--client-timeout-ms MS]
//                   [--client-budget-ms MS] [--bricks I/N] [--curve-secret FILE --allow-keys DIR]
//                   [--timings FILE.json] [probe options] [--probe-visibility R]
//                   [--probe-relocation] [schedule options]
//
// The probe server: the frame loop's in-process probe source (probe_source.h) with the probe
// stream's publisher (net/) as its only consumer, and no rasterizer. Each tick (--fps) it poses
// the scene, plans the probes from the union of its clients' views (each client's views ranked
// like a display's) within --budget-ms (or --client-budget-ms per connected client, so that each
// client's views converge as fast as if it were alone: tests/probes/test_scheduler_clients.cpp),
// runs the one probe update, and publishes the delta of
// what changed (net/published_probes.h: --delta-threshold), each sent probe with its relocation
// offset and, when its map moved past --moment-threshold, its distance moments
// (--probe-visibility, default 8 as render's); between ticks it answers snapshot
// requests and takes the clients' views. A client silent for --client-timeout-ms stops counting.
// With no client it idles (publishes empty deltas as heartbeats, traces nothing); --frames N
// instead makes N updates whatever the clients, then serves their result. --seconds S stops it
// after S seconds, SIGINT / SIGTERM at once; either way --timings is written (per tick: whether
// it updated, probe ms, probes traced / sent / sent with their maps / deactivated / held back,
// bytes, clients).
// The grid is cut into bricks of 4x4x4 probes (net/bricks.h), each published as a stream of its
// own under its topic; --bricks I/N makes this server own only share I of N (brick b when
// b mod N == I): it traces, publishes and answers snapshots for those alone, so N servers with
// the same scene and grid and shares 0/N .. N-1/N serve the whole volume between them.
// It binds loopback unless told otherwise; a non-loopback --bind needs keys or --insecure. With
// --curve-secret (the server's .key of `ddish keys`) and --allow-keys (a folder of clients' .pub
// files) both sockets speak CurveZMQ and a ZAP handler refuses every client key not listed.
#include <chrono>
#include <cmath>
#include <algorithm>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <memory>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "app/lighting_options.h"
#include "app/probe_options.h"
#include "app/probe_setup.h"
#include "app/probe_source.h"
#include "app/scene_identity.h"
#include "app/schedule_options.h"
#include "io/atomic_file.h"
#include "net/curve_keys.h"
#include "net/bricks.h"
#include "net/endpoint.h"
#include "net/probe_server.h"
#include "net/published_probes.h"
#include "app/tracer_choice.h"
#include "probes/probe_tracer.h"
#include "probes/probe_volume.h"
#include "probes/scheduler.h"
#include "probes/tracer_source.h"
#include "scene/gltf_loader.h"
#include "scene/scene.h"
#include "trace/tracer.h"

namespace ddish::app {
namespace {

volatile std::sig_atomic_t g_stop = 0;
void request_stop(int) { g_stop = 1; }

struct ServeArgs {
  std::string scene;
  std::string bind = "tcp://127.0.0.1:5570";
  bool insecure = false;
  ProbeArgs probe;
  ScheduleArgs schedule;
  LightingArgs lighting;  // --sky, --environment: the light the probes are traced in
  std::string tracer = "auto";  // --tracer
  double fps = 30.0;
  double time = 0.0;
  int frames = 0;
  double seconds = 0.0;
  std::string encoding = "compact";
  bool zstd = false;
  float threshold = 0.01f;
  float floor = 0.0f;
  float moment_threshold = 0.005f;
  int client_timeout_ms = 2000;
  double client_budget_ms = 0.0;  // > 0: the tick's budget is this x the connected clients
  std::string timings;
  std::string curve_secret;
  std::string allow_keys;
  std::string bricks = "0/1";
};

void check(const ServeArgs& a) {
  check_probe_options(a.probe);
  check_schedule_options(a.schedule);
  sky_radiance(a.lighting);  // a malformed --sky or a missing --environment file, before the load
  if (!(a.fps > 0.0) || a.fps > 1000.0) throw std::invalid_argument("--fps must be in (0, 1000]");
  if (a.frames < 0 || a.seconds < 0.0) throw std::invalid_argument("--frames and --seconds must be >= 0");
  if (!net::parse_encoding(a.encoding))
    throw std::invalid_argument("--encoding must be fp16, shared-exponent or compact, got '" + a.encoding + "'");
  if (!(a.threshold >= 0.0f) || !(a.floor >= 0.0f) || !(a.moment_threshold >= 0.0f))
    throw std::invalid_argument("--delta-threshold, --delta-floor and --moment-threshold must be >= 0");
  if (a.client_timeout_ms < 1) throw std::invalid_argument("--client-timeout-ms must be >= 1");
  if (!(a.client_budget_ms >= 0.0) || !std::isfinite(a.client_budget_ms))
    throw std::invalid_argument("--client-budget-ms must be a finite number >= 0");
  if (a.curve_secret.empty() != a.allow_keys.empty())
    throw std::invalid_argument("--curve-secret and --allow-keys go together");
  net::parse_brick_share(a.bricks);
  const net::Endpoint e = net::parse_endpoint(a.bind);
  if (!e.loopback() && !a.insecure && a.curve_secret.empty())
    throw std::invalid_argument("--bind " + a.bind +
                                " is not a loopback address: serving it needs --curve-secret and --allow-keys, or --insecure");
}

struct TickRecord {
  std::uint64_t tick = 0;
  bool updated = false;
  double probe_ms = 0.0;
  double tick_ms = 0.0;
  double busy_ms = 0.0;  // the tick's work: update, publish and the requests answered (not idling)
  double budget_ms = 0.0;  // the scheduler's budget for this tick's update (0: none)
  std::uint32_t traced = 0;
  net::PublishStats published;
  std::size_t clients = 0;
};

void write_timings(const std::string& path, const std::vector<TickRecord>& ticks,
                   const net::ProbeServer& server, double seconds, std::size_t bricks) {
  nlohmann::ordered_json doc;
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  std::uint64_t updates = 0;
  for (const TickRecord& t : ticks) {
    updates += t.updated;
    list.push_back({{"tick", t.tick},
                    {"updated", t.updated},
                    {"probe_ms", t.probe_ms},
                    {"tick_ms", t.tick_ms},
                    {"busy_ms", t.busy_ms},
                    {"budget_ms", t.budget_ms},
                    {"probes_traced", t.traced},
                    {"probes_sent", t.published.sent},
                    {"maps_sent", t.published.maps},
                    {"probes_deactivated", t.published.deactivated},
                    {"probes_held_back", t.published.held_back},
                    {"probes_saturated", t.published.saturated},
                    {"bytes", t.published.bytes},
                    {"clients", t.clients}});
  }
  doc["ticks"] = std::move(list);
  doc["summary"] = {{"ticks", ticks.size()},
                    {"updates", updates},
                    {"seconds", seconds},
                    {"bricks", bricks},  // owned: one frame (88-byte header) each per tick
                    {"bytes_published", server.bytes_published()},
                    {"bytes_per_second", seconds > 0.0 ? double(server.bytes_published()) / seconds : 0.0},
                    {"snapshots_sent", server.snapshots_sent()},
                    {"malformed_requests", server.malformed_requests()}};
  io::write_file_atomically(path, doc.dump(2) + "\n");
}

int run_serve(const ServeArgs& a) {
  check(a);
  if (!a.timings.empty()) io::check_writable_file(a.timings);  // before the scene loads
  scene::Scene s = scene::load_scene(a.scene);
  const std::uint64_t geometry = geometry_identity(s);
  const std::string environment = apply_lighting(s, a.lighting);
  std::fprintf(stderr, "serve: %s\n", environment.c_str());
  s.pose(a.time);
  const Placement placement = place_probes(a.probe, s);
  const std::uint64_t identity = scene_identity(geometry, placement.grid, a.probe.sh_order);

  trace::PathOptions path_options;
  path_options.max_bounces = a.probe.bounces;
  const TracerDecision tracer = choose_tracer(a.tracer, std::nullopt);
  std::fprintf(stderr, "serve: probe tracer %s\n", tracer.why.c_str());
  ProbeEngine engine(tracer.kind, s, path_options, update_options(a.probe), std::nullopt);
  const double budget_ms = frame_budget_ms(a.schedule, std::nullopt);
  probes::Scheduler scheduler(scheduler_options(a.schedule, a.probe, budget_ms));
  // With distance moments (--probe-visibility, either tracer) and relocation offsets, which every
  // frame carries: a client interpolates with the visibility an in-process render has.
  probes::ProbeVolume volume = local_volume(a.probe, placement.grid);
  if (const std::uint32_t n = leave_out_empty_probes(volume, s); n > 0) {
    const scene::PlanItem item = empty_probes_item(n, volume.grid());
    std::fprintf(stderr, "serve: left out %s: %s\n", item.what.c_str(), item.why.c_str());
  }
  InProcessProbes probes_source(
      engine, scheduler,
      [&](const probes::FramePlan& plan) {
        return frame_update_options(a.schedule, a.probe, plan.samples, plan.hysteresis);
      },
      volume);

  const std::uint64_t stream = (std::uint64_t(std::random_device{}()) << 32) ^ std::random_device{}() ^
                               std::uint64_t(net::steady_now_us());
  net::StreamOptions so;
  so.encoding = *net::parse_encoding(a.encoding);
  so.zstd = a.zstd;
  so.threshold = a.threshold;
  so.floor = a.floor;
  so.moment_threshold = a.moment_threshold;
  // The bricks of this server's share: one stream each. The others' probes are inactive here,
  // so the scheduler never plans them.
  const net::BrickShare share = net::parse_brick_share(a.bricks);
  const net::BrickLayout layout(placement.grid);
  std::vector<std::uint32_t> owned;
  std::vector<int> stream_of(layout.brick_count(), -1);
  std::vector<net::PublishedProbes> published;
  for (std::uint32_t b = 0; b < layout.brick_count(); ++b) {
    std::vector<std::uint32_t> probes = layout.probes(b);
    if (!share.owns(b)) {
      for (std::uint32_t i : probes) volume.deactivate(i, false);
      continue;
    }
    stream_of[b] = int(owned.size());
    owned.push_back(b);
    published.emplace_back(volume, identity, stream, so, std::move(probes));
  }
  std::optional<net::CurveServerKeys> curve;
  if (!a.curve_secret.empty())
    curve = net::CurveServerKeys{net::read_secret_key(a.curve_secret).secret_z85,
                                 net::read_allowed_keys(a.allow_keys)};
  net::ProbeServer server({.bind = a.bind,
                           .client_timeout_ms = a.client_timeout_ms,
                           .log = [](const std::string& line) { std::fprintf(stderr, "serve: %s\n", line.c_str()); },
                           .curve = curve,
                           .send_hwm = int(std::max<std::size_t>(64, 8 * owned.size())),
                           .info = net::PublishedProbes(volume, identity, stream, so).description(),
                           .info_bounds = net::encode_grid_bounds(placement.grid.bounds())});
  if (curve)
    std::fprintf(stderr, "serve: CurveZMQ, %zu client keys allowed (%s)\n", curve->allowed_z85.size(),
                 a.allow_keys.c_str());
  const net::Endpoint endpoint = net::parse_endpoint(a.bind);
  const auto& g = placement.grid;
  std::fprintf(stderr,
               "serve: %s on %s (requests %s), scene identity %016llx, stream %016llx; probes %dx%dx%d "
               "(%s), L%d, visibility %s, %s%s, delta threshold %g (floor %g), moment threshold %g; bricks %s: %zu of %u; %s\n",
               s.path.c_str(), endpoint.publisher().c_str(), endpoint.requests().c_str(),
               static_cast<unsigned long long>(identity), static_cast<unsigned long long>(stream),
               g.counts().x, g.counts().y, g.counts().z, placement.how.c_str(), a.probe.sh_order,
               volume.has_moments() ? fmt::format("{0}x{0} moments over {1:g} m", volume.moment_resolution(),
                                                  volume.moment_range()).c_str()
                                    : "off",
               a.encoding.c_str(), a.zstd ? " + zstd" : "", a.threshold, a.floor, a.moment_threshold, a.bricks.c_str(),
               owned.size(), layout.brick_count(),
               a.frames > 0 ? fmt::format("{} updates, then serving them", a.frames).c_str()
                            : "updating while clients are connected");
  std::fflush(stderr);

  std::signal(SIGINT, request_stop);
  std::signal(SIGTERM, request_stop);
  const auto start = std::chrono::steady_clock::now();
  const auto period = std::chrono::duration<double, std::milli>(1000.0 / a.fps);
  std::vector<TickRecord> ticks;
  std::int64_t last_update_end_us = net::steady_now_us();
  double scene_time = a.time;
  int updates = 0;
  const auto snapshot = [&](std::uint32_t brick) {
    return brick < stream_of.size() && stream_of[brick] >= 0 ? published[std::size_t(stream_of[brick])].snapshot()
                                                            : std::vector<std::uint8_t>{};
  };
  std::uint64_t ticks_done = 0;
  for (std::uint64_t tick = 1; !g_stop; ++tick) {
    const auto tick_start = std::chrono::steady_clock::now();
    if (a.seconds > 0.0 && std::chrono::duration<double>(tick_start - start).count() >= a.seconds) break;
    TickRecord rec;
    rec.tick = tick;
    rec.clients = server.clients();
    const bool update = a.frames > 0 ? updates < a.frames : rec.clients > 0;
    if (update) {
      metrics::FrameTimings timings;
      FrameCounts counts;
      scene_time = a.time + double(updates) / a.fps;
      if (a.client_budget_ms > 0.0) {
        // One client's budget per client, within the whole tick's --budget-ms where given.
        rec.budget_ms = a.client_budget_ms * double(std::max<std::size_t>(rec.clients, 1));
        if (budget_ms > 0.0) rec.budget_ms = std::min(rec.budget_ms, budget_ms);
        probes_source.set_frame_budget(rec.budget_ms);
      } else {
        rec.budget_ms = budget_ms;
      }
      std::vector<int> moved = s.pose(scene_time);
      probes_source.posed(s, moved, timings);
      const ProbeStep step = probes_source.update(server.views(), true, timings, counts);
      last_update_end_us = net::steady_now_us();
      probes_source.finished(updates, timings, step, true, counts);
      rec.updated = true;
      rec.probe_ms = timings.stage_ms("probe_update");
      rec.traced = counts.probes_traced;
      ++updates;
    }
    for (std::size_t k = 0; k < owned.size(); ++k) {
      net::PublishStats stats;
      server.publish(owned[k], published[k].publish(volume, tick, last_update_end_us, scene_time, &stats));
      rec.published.sent += stats.sent;
      rec.published.maps += stats.maps;
      rec.published.deactivated += stats.deactivated;
      rec.published.held_back += stats.held_back;
      rec.published.saturated += stats.saturated;
      rec.published.bytes += stats.bytes;
    }
    const double used_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - tick_start).count();
    const double request_ms = server.serve_requests(int(std::max(0.0, period.count() - used_ms)), snapshot);
    rec.tick_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - tick_start).count();
    rec.busy_ms = used_ms + request_ms;
    if (rec.updated && (updates <= 3 || updates % 100 == 0 || updates == a.frames))
      std::fprintf(stderr, "serve: update %d: %u probes traced in %.1f ms, %u sent (%zu bytes), %zu clients\n",
                   updates, rec.traced, rec.probe_ms, rec.published.sent, rec.published.bytes, rec.clients);
    // Kept only for --timings: a server runs for days, and an idle tick must cost no memory.
    ticks_done = tick;
    if (!a.timings.empty()) ticks.push_back(rec);
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::fprintf(stderr, "serve: stopped after %llu ticks (%d updates), %llu bytes published, %llu snapshots\n",
               static_cast<unsigned long long>(ticks_done), updates, static_cast<unsigned long long>(server.bytes_published()),
               static_cast<unsigned long long>(server.snapshots_sent()));
  if (!a.timings.empty()) {
    write_timings(a.timings, ticks, server, seconds, owned.size());
    std::printf("wrote %s\n", a.timings.c_str());
  }
  return 0;
}

Action make_serve(CLI::App& root) {
  auto a = std::make_shared<ServeArgs>();
  CLI::App* cmd = root.add_subcommand("serve", "probe server: probes path-traced and streamed to ddish view clients");
  cmd->add_option("scene", a->scene, "glTF 2.0 scene (.gltf or .glb)")->required()->check(CLI::ExistingFile);
  cmd->add_option("--bind", a->bind, "publisher address tcp://HOST:PORT (PORT+1: requests)")->capture_default_str();
  cmd->add_flag("--insecure", a->insecure, "allow a non-loopback --bind without keys");
  add_probe_options(*cmd, a->probe);
  add_visibility_options(*cmd, a->probe);
  add_schedule_options(*cmd, a->schedule);
  cmd->add_option("--fps", a->fps, "ticks per second (one probe update and one published delta each)")
      ->capture_default_str();
  cmd->add_option("--time", a->time, "scene time of the first update (seconds); update k shows time + k / fps")
      ->capture_default_str();
  cmd->add_option("--frames", a->frames, "make this many updates whatever the clients, then serve them (0: update while clients are connected)")
      ->capture_default_str();
  cmd->add_option("--seconds", a->seconds, "stop after this many seconds (0: run until interrupted)")
      ->capture_default_str();
  cmd->add_option("--encoding", a->encoding, "coefficient encoding: fp16, shared-exponent or compact (distance moments travel as fp16 whatever it is)")->capture_default_str();
  cmd->add_flag("--zstd", a->zstd, "compress every frame's payload with zstd");
  cmd->add_option("--delta-threshold", a->threshold,
                  "re-send a probe when a coefficient moved more than this fraction of its largest L0")
      ->capture_default_str();
  cmd->add_option("--moment-threshold", a->moment_threshold,
                  "re-send a probe with its distance-moment map when the map's texels moved more than this "
                  "fraction of the moment range, root mean square over the map (mean distance and spread)")
      ->capture_default_str();
  cmd->add_option("--delta-floor", a->floor, "... or more than this absolute amount, whichever is larger")
      ->capture_default_str();
  cmd->add_option("--client-timeout-ms", a->client_timeout_ms, "a client silent for this long stops counting")
      ->capture_default_str();
  cmd->add_option("--client-budget-ms", a->client_budget_ms,
                  "probe-update budget per connected client (visibility schedule): the tick's budget is MS x "
                  "clients, at most --budget-ms; 0: --budget-ms alone")
      ->capture_default_str();
  cmd->add_option("--bricks", a->bricks,
                  "serve share I of N of the probe bricks (4x4x4 probes each; brick b when b mod N == I); "
                  "N servers of the same scene and grid serve the whole volume")
      ->capture_default_str();
  add_lighting_options(*cmd, a->lighting, /*exposure=*/false);
  add_tracer_option(*cmd, a->tracer);
  cmd->add_option("--timings", a->timings, "write a per-tick record as JSON here");
  cmd->add_option("--curve-secret", a->curve_secret, "the server's secret key (ddish keys): CurveZMQ on")
      ->check(CLI::ExistingFile);
  cmd->add_option("--allow-keys", a->allow_keys, "folder of the client public keys (.pub) the server admits")
      ->check(CLI::ExistingDirectory);
  return [a]() { return run_serve(*a); };
}

}  // namespace

DDISH_COMMAND(60, make_serve);

}  // namespace ddish::app
