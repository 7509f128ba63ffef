// The probe server's sockets (ZeroMQ, the zguide's Clone pattern):
//   - a PUB socket at the endpoint's publisher address sends every probe frame (one delta per
//     tick, empty or not: the chain of base frames tells a client that it missed one);
//   - a ROUTER socket at the request address answers snapshot requests with a keyframe of the
//     last published frame and the server's clock, and takes each client's views.
// Requests are multipart: ["SNAP", u64 client time µs] is answered ["SNAP", the same 8 bytes,
// i64 server steady-clock time µs, keyframe]; ["VIEW", view message (view_message.h)] replaces
// that client's views. A client whose last message is older than the timeout stops counting.
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

  void publish(std::span<const std::uint8_t> frame);

  // Answers requests for timeout_ms (polls at least once; returns early when a signal interrupts
  // the wait); `snapshot` makes each reply's keyframe.
  // Returns the milliseconds spent handling requests (the rest of timeout_ms was idle).
  double serve_requests(int timeout_ms, const std::function<std::vector<std::uint8_t>()>& snapshot);

  // The union of the views of the clients heard from within the timeout.
  std::vector<scene::View> views() const;
  std::size_t clients() const;

  std::uint64_t bytes_published() const;
  std::uint64_t snapshots_sent() const;
  std::uint64_t malformed_requests() const;
  std::uint64_t refused_keys() const;  // CURVE handshakes the ZAP handler refused

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ddish::net
