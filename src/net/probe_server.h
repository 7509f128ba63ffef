// The probe server's sockets (ZeroMQ, the zguide's Clone pattern):
//   - a PUB socket at the endpoint's publisher address sends every probe frame as two parts,
//     [brick topic (bricks.h), frame]: one delta per owned brick per tick, empty or not (the
//     chain of base frames tells a client that it missed one); subscribers filter by topic;
//   - a ROUTER socket at the request address answers snapshot requests with keyframes of the
//     last published frame of the bricks asked for that it owns and the server's clock, and
//     takes each client's views.
// Requests are multipart: ["SNAP", u64 client time µs, u32 bricks wanted...] is answered
// ["SNAP", the same 8 bytes, i64 server steady-clock time µs, then topic and keyframe of each
// wanted brick the server owns]; ["VIEW", view message (view_message.h)] replaces that client's
// views; ["INFO"] is answered ["INFO", an empty keyframe of the stream, the grid's bounds] (the
// keyframe's header is the stream's description: protocol version, scene identity, grid counts,
// SH order, moment resolution and range; the bounds are encode_grid_bounds's 24 bytes), which a
// client asks for before it places its probes and sizes its volume. A client whose last message is older than the timeout stops counting.
// ZMTP heartbeats run on every connection. Malformed requests are dropped and counted, with one
// log line per kind.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <vector>

#include "scene/view.h"

namespace ddish::net {

// CurveZMQ on both sockets: the server's secret key and the client public keys it admits (a ZAP
// handler refuses every other key).
struct CurveServerKeys {
  std::string secret_z85;
  std::set<std::string> allowed_z85;
};

struct ServerOptions {
  std::string bind = "tcp://127.0.0.1:5570";
  int heartbeat_ms = 250;
  int client_timeout_ms = 2000;
  std::function<void(const std::string&)> log;  // one line per event
  std::optional<CurveServerKeys> curve;          // none: plaintext
  // Frames queued per subscriber before the publisher drops them (the subscriber then sees a gap
  // and takes a snapshot): a few ticks of every owned brick (serve: 8 x bricks, at least 64).
  int send_hwm = 64;
  // The answer to INFO requests: an empty keyframe of this stream
  // (PublishedProbes::description()); empty: INFO goes unanswered.
  std::vector<std::uint8_t> info;
  // The INFO reply's third part: the grid's bounds (encode_grid_bounds); empty: a reply of two
  // parts (a client then places its probes itself).
  std::vector<std::uint8_t> info_bounds;
};

// Microseconds of the steady clock: the time base of server_time_us and of the client's clock.
std::int64_t steady_now_us();

class ProbeServer {
 public:
  // Binds both sockets; throws std::runtime_error naming the address when it cannot.
  explicit ProbeServer(const ServerOptions& options);
  ~ProbeServer();
  ProbeServer(const ProbeServer&) = delete;
  ProbeServer& operator=(const ProbeServer&) = delete;

  // Publishes a frame of `brick` under its topic.
  void publish(std::uint32_t brick, std::span<const std::uint8_t> frame);

  // The keyframe of a brick for a snapshot reply; empty when the server does not own it.
  using SnapshotFn = std::function<std::vector<std::uint8_t>(std::uint32_t brick)>;
  // Answers requests for timeout_ms (polls at least once; returns early when a signal interrupts
  // the wait); `snapshot` makes each reply's keyframes.
  // Returns the milliseconds spent handling requests (the rest of timeout_ms was idle).
  double serve_requests(int timeout_ms, const SnapshotFn& snapshot);

  // The union of the views of the clients heard from within the timeout.
  std::vector<scene::View> views() const;
  std::size_t clients() const;

  std::uint64_t bytes_published() const;
  std::uint64_t snapshots_sent() const;  // snapshot replies
  std::uint64_t malformed_requests() const;
  std::uint64_t refused_keys() const;  // CURVE handshakes the ZAP handler refused

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ddish::net
