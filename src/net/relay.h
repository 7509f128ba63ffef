// The relay: a standard ZeroMQ forwarder (zmq_proxy_steerable over an XSUB and an XPUB socket)
// between probe servers' publishers and many clients. The XSUB socket connects to every
// server's publisher, the XPUB socket binds one address the clients subscribe at
// (`view --relay`). Subscriptions (the brick topics of bricks.h) pass upstream through XPUB ->
// XSUB, merged (a topic goes to the servers once, whatever the number of clients that want it,
// and leaves when the last one unsubscribes), so each server still sends only the bricks some
// client needs, once per relay. A restarted server gets the subscriptions again when the XSUB
// socket reconnects (every 100 ms). Snapshots and views do not pass here: clients ask each
// server directly. The relay speaks plaintext.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace ddish::net {

struct RelayOptions {
  std::vector<std::string> upstream;  // the servers' publisher addresses, tcp://HOST:PORT
  std::string bind = "tcp://127.0.0.1:5600";
  int heartbeat_ms = 250;
  // Messages queued per client (and from each server) before the relay drops them; a client
  // that missed one takes a snapshot. 20,000 is five ticks of a 4,096-brick volume, about 40 MB
  // of compact bricks.
  int hwm = 20000;
};

// zmq_proxy's counts: messages (a brick's [topic, frame] is one) and bytes, frontend (from the
// servers) and backend (to the clients).
struct RelayStats {
  std::uint64_t messages_in = 0, bytes_in = 0;    // received from the servers
  std::uint64_t messages_out = 0, bytes_out = 0;  // sent to the clients (once each, however many take it)
  std::uint64_t subscriptions = 0;             // subscription messages passed upstream
};

class Relay {
 public:
  // Binds and connects; throws std::runtime_error naming the address when it cannot.
  explicit Relay(const RelayOptions& options);
  ~Relay();
  Relay(const Relay&) = delete;
  Relay& operator=(const Relay&) = delete;

  // Forwards until `stop` returns true (asked every 20 ms; SIGINT and SIGTERM reach the caller's
  // thread, not the forwarder's); returns the counts.
  RelayStats run(const std::function<bool()>& stop);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ddish::net
