// The client side of the probe stream (ZeroMQ): a SUB socket on the servers' publishers (or on
// one relay that forwards them, `ddish relay`) and a DEALER on each server's request socket
// (probe_server.h). The grid is cut into bricks (bricks.h), each a stream of its own, owned by
// one of the servers: the client subscribes to the topics of the bricks its views need (all of
// them until it is given views), asks every server for snapshots of those it does not hold
// (each answers for the bricks it owns), and follows each brick's deltas from there
// (probe_mirror.h, one mirror per brick); a delta it cannot apply (a lost message, a restarted
// server) makes it ask again for that brick. Views go to every server. Per server, its clocks:
//   - liveness comes from the transport: the subscription's connection dropping (a closed
//     socket, or ZMTP heartbeats unanswered for 4 x heartbeat_ms) is a lost server (one log
//     line); the probes are kept, and snapshot requests go on until a keyframe comes back (one
//     log line). Silence alone is not a loss: a server whose update takes longer than stale_ms
//     (its first one, a big scene) is slow, not gone, and its next delta still applies;
//   - staleness: milliseconds since the last message from the server, reported every frame;
//     past stale_ms with the connection up, one log line says the server is slow;
//   - the server's clock: each snapshot reply carries the server's steady-clock time, and the
//     offset is the reply's time less the midpoint of the request's round trip, so the age of
//     a probe update (server trace end -> now) does not assume a shared clock.
// Every incoming message goes through decode_frame; a refused one is dropped and counted by
// kind, with one log line per kind. A server of another scene is refused the same way.
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "net/probe_frame.h"
#include "probes/probe_volume.h"
#include "scene/view.h"

namespace ddish::net {

// CurveZMQ: the server's public key and this client's key pair.
struct CurveClientKeys {
  std::string server_public_z85;
  std::string public_z85;
  std::string secret_z85;
};

struct ClientOptions {
  std::string connect = "tcp://127.0.0.1:5570";  // one server, or several: A,B,...
  std::string relay;  // a relay's publisher (`ddish relay`) for the frames; empty: each server's
  int heartbeat_ms = 250;
  int stale_ms = 1000;          // no message for this long, connection up: say the server is slow
  int snapshot_retry_ms = 250;  // between snapshot requests while unsynced
  std::function<void(const std::string&)> log;
  std::optional<CurveClientKeys> curve;  // none: plaintext
  // The views known at start: the subscriptions from the first connection on are the bricks
  // they need. None: every brick, until send_views.
  std::vector<scene::View> views;
};

struct ClientPoll {
  std::vector<std::uint32_t> changed;  // probes set by the frames applied (increasing)
  std::uint32_t frames_applied = 0;
  std::uint32_t keyframes_applied = 0;
  std::uint64_t bytes = 0;             // of every message received
};

// A server's description of its stream: the header of its empty keyframe (scene identity, grid
// counts, SH order, moment resolution and range) and, from servers that send them, the grid's
// bounds as placed.
struct StreamDescription {
  FrameHeader header;
  std::optional<scene::Aabb> bounds;
};

// Asks every server of options.connect for its stream's description (the INFO request,
// probe_server.h) and returns the first valid answer within wait_ms: what a client places its
// probes by and sizes its volume by before it takes any frame. nullopt when none answers in
// time; *problem then says why (no answer, or the answer refused: another protocol version,
// bounds that are not 6 finite ordered floats, say).
std::optional<StreamDescription> ask_stream_description(const ClientOptions& options, int wait_ms,
                                                        std::string* problem = nullptr);

class ProbeClient {
 public:
  // `volume` (borrowed) is the client's volume of its own scene, `scene_id` its identity.
  ProbeClient(const ClientOptions& options, probes::ProbeVolume& volume, std::uint64_t scene_id);
  ~ProbeClient();
  ProbeClient(const ProbeClient&) = delete;
  ProbeClient& operator=(const ProbeClient&) = delete;

  // Takes every waiting message; waits up to wait_ms for the first one that brings probes
  // (0: does not wait), or with `until_synced` until every needed brick is held (a first frame:
  // the snapshots of several servers). Asks for snapshots as needed. A signal ends the wait
  // early.
  ClientPoll poll(int wait_ms, bool until_synced = false);
  // Sends the views to every server and subscribes to the bricks they need (no views: no
  // change).
  void send_views(const std::vector<scene::View>& views);

  bool synced() const;                 // holds every needed brick's state of its current server
  bool ever_synced() const;            // has held probes from a server
  std::uint64_t server_frame() const;  // the newest frame held
  // The bricks subscribed to (increasing), and the probe frames received per brick, applied or
  // not: every message the subscription delivered under its topic, and snapshot keyframes.
  std::vector<std::uint32_t> subscribed_bricks() const;
  std::vector<std::uint64_t> frames_per_brick() const;
  double stale_ms() const;             // since the last message (0 before the first)
  // Age of the held probes: now less the end of their probe update, in the client's clock
  // (nullopt before a clock offset is known).
  std::optional<double> probe_age_ms() const;
  std::uint64_t snapshots() const;     // keyframes applied
  std::uint64_t reconnects() const;    // times the server came back after being lost
  std::uint64_t rejected(RejectKind kind) const;
  std::uint64_t rejected_total() const;

 private:
  struct Impl;
  void poll_until(std::chrono::steady_clock::time_point end, bool until_synced, ClientPoll& out);
  std::unique_ptr<Impl> impl_;
};

}  // namespace ddish::net
