#include "net/relay.h"

#include <pthread.h>
#include <signal.h>

#include <array>
#include <chrono>
#include <cstring>
#include <stdexcept>
#include <thread>

#include <fmt/format.h>
#include <zmq.hpp>
#include <zmq_addon.hpp>

#include "net/endpoint.h"

namespace ddish::net {

struct Relay::Impl {
  RelayOptions options;
  zmq::context_t context{1};
  zmq::socket_t frontend{context, zmq::socket_type::xsub};
  zmq::socket_t backend{context, zmq::socket_type::xpub};
  zmq::socket_t control{context, zmq::socket_type::pair};        // ours
  zmq::socket_t proxy_control{context, zmq::socket_type::pair};  // the forwarder's
};

Relay::Relay(const RelayOptions& options) : impl_(std::make_unique<Impl>()) {
  impl_->options = options;
  for (zmq::socket_t* s : {&impl_->frontend, &impl_->backend}) {
    s->set(zmq::sockopt::linger, 0);
    s->set(zmq::sockopt::heartbeat_ivl, options.heartbeat_ms);
    s->set(zmq::sockopt::heartbeat_timeout, 4 * options.heartbeat_ms);
    s->set(zmq::sockopt::heartbeat_ttl, 4 * options.heartbeat_ms);
    s->set(zmq::sockopt::sndhwm, options.hwm);
    s->set(zmq::sockopt::rcvhwm, options.hwm);
  }
  impl_->frontend.set(zmq::sockopt::reconnect_ivl, 100);
  impl_->frontend.set(zmq::sockopt::reconnect_ivl_max, 0);
  const Endpoint bind = parse_endpoint(options.bind);
  try {
    impl_->backend.bind(bind.publisher());
  } catch (const zmq::error_t& e) {
    throw std::runtime_error("cannot bind " + bind.publisher() + ": " + e.what());
  }
  for (const std::string& address : options.upstream) impl_->frontend.connect(parse_endpoint(address).publisher());
  const std::string inproc = fmt::format("inproc://ddish-relay-{}", static_cast<void*>(this));
  impl_->control.bind(inproc);
  impl_->proxy_control.connect(inproc);
}

Relay::~Relay() = default;

RelayStats Relay::run(const std::function<bool()>& stop) {
  // The forwarder's thread starts with SIGINT and SIGTERM blocked, so that they interrupt the
  // caller (its stop flag) and never the proxy.
  sigset_t block, old;
  sigemptyset(&block);
  sigaddset(&block, SIGINT);
  sigaddset(&block, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &block, &old);
  Impl& s = *impl_;
  std::thread proxy([&s] {
    zmq_proxy_steerable(s.frontend.handle(), s.backend.handle(), nullptr, s.proxy_control.handle());
  });
  pthread_sigmask(SIG_SETMASK, &old, nullptr);
  while (!stop()) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  RelayStats stats;
  std::vector<zmq::message_t> parts;
  s.control.send(zmq::str_buffer("STATISTICS"));
  if (zmq::recv_multipart(s.control, std::back_inserter(parts)) && parts.size() == 8) {
    std::array<std::uint64_t, 8> v{};
    for (std::size_t k = 0; k < 8; ++k)
      if (parts[k].size() == 8) std::memcpy(&v[k], parts[k].data(), 8);
    // zmq_proxy's order: frontend in (msgs, bytes), frontend out, backend in, backend out.
    stats.messages_in = v[0];
    stats.bytes_in = v[1];
    stats.subscriptions = v[2];
    stats.messages_out = v[6];
    stats.bytes_out = v[7];
  }
  s.control.send(zmq::str_buffer("TERMINATE"));
  proxy.join();
  return stats;
}

}  // namespace ddish::net
