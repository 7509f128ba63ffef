#include "net/probe_server.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <map>
#include <set>
#include <stdexcept>

#include <zmq.hpp>
#include <zmq_addon.hpp>

#include "net/bricks.h"
#include "net/byte_io.h"
#include "net/endpoint.h"
#include "net/view_message.h"
#include "net/zap_handler.h"

namespace ddish::net {

std::int64_t steady_now_us() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

struct ProbeServer::Impl {
  struct Client {
    std::int64_t last_heard_us = 0;
    std::vector<scene::View> views;
  };
  ServerOptions options;
  zmq::context_t context{1};
  std::unique_ptr<ZapHandler> zap;  // before the sockets: they are closed first
  zmq::socket_t publisher{context, zmq::socket_type::pub};
  zmq::socket_t requests{context, zmq::socket_type::router};
  std::map<std::string, Client> clients;
  std::set<std::string> logged_kinds;
  std::uint64_t bytes = 0, snapshots = 0, malformed = 0;

  void log(const std::string& line) {
    if (options.log) options.log(line);
  }
  void reject(const std::string& kind, const std::string& detail) {
    ++malformed;
    if (logged_kinds.insert(kind).second)
      log("dropped a malformed request (" + kind + "): " + detail + "; further ones are counted");
  }
  void forget_silent_clients() {
    const std::int64_t now = steady_now_us();
    for (auto it = clients.begin(); it != clients.end();)
      it = now - it->second.last_heard_us > std::int64_t(options.client_timeout_ms) * 1000
               ? clients.erase(it)
               : std::next(it);
  }
  void handle(std::vector<zmq::message_t>& parts, const SnapshotFn& snapshot) {
    if (parts.size() < 2) return reject("no-type", "a request without a type");
    const std::string id = parts[0].to_string();
    const std::string type = parts[1].to_string();
    if (type == "SNAP") {
      if (parts.size() != 4 || parts[2].size() != 8 || parts[3].size() % 4 != 0)
        return reject("bad-snapshot-request",
                      "a snapshot request without its 8-byte client time and its u32 bricks");
      std::vector<std::uint8_t> now;
      ByteWriter(now).i64(steady_now_us());
      std::vector<std::string> topics;
      std::vector<std::vector<std::uint8_t>> keyframes;
      ByteReader wanted({static_cast<const std::uint8_t*>(parts[3].data()), parts[3].size()});
      for (std::size_t k = 0; k < parts[3].size() / 4; ++k) {
        std::uint32_t brick = 0;
        wanted.u32(brick);
        std::vector<std::uint8_t> keyframe = snapshot(brick);
        if (keyframe.empty()) continue;  // not this server's
        topics.push_back(brick_topic(brick));
        keyframes.push_back(std::move(keyframe));
      }
      std::vector<zmq::const_buffer> reply = {zmq::buffer(id), zmq::str_buffer("SNAP"),
                                              zmq::buffer(parts[2].data(), parts[2].size()),
                                              zmq::buffer(now)};
      for (std::size_t k = 0; k < topics.size(); ++k) {
        reply.push_back(zmq::buffer(topics[k]));
        reply.push_back(zmq::buffer(keyframes[k]));
      }
      if (zmq::send_multipart(requests, reply, zmq::send_flags::dontwait)) {
        ++snapshots;
        for (const auto& k : keyframes) bytes += k.size();
      }
      clients[id].last_heard_us = steady_now_us();
    } else if (type == "VIEW") {
      if (parts.size() != 3) return reject("bad-view-message", "a view message of several parts");
      std::vector<scene::View> views;
      std::string problem;
      if (!decode_views({static_cast<const std::uint8_t*>(parts[2].data()), parts[2].size()}, views, problem))
        return reject("bad-view-message", problem);
      Client& c = clients[id];
      c.views = std::move(views);
      c.last_heard_us = steady_now_us();
    } else if (type == "INFO") {
      if (parts.size() != 2) return reject("bad-info-request", "an INFO request of several parts");
      if (options.info.empty()) return;
      std::vector<zmq::const_buffer> reply = {zmq::buffer(id), zmq::str_buffer("INFO"), zmq::buffer(options.info)};
      if (!options.info_bounds.empty()) reply.push_back(zmq::buffer(options.info_bounds));
      zmq::send_multipart(requests, reply, zmq::send_flags::dontwait);
      clients[id].last_heard_us = steady_now_us();
    } else {
      reject("unknown-request", "request type '" + type.substr(0, 16) + "'");
    }
  }
};

ProbeServer::ProbeServer(const ServerOptions& options) : impl_(std::make_unique<Impl>()) {
  impl_->options = options;
  const Endpoint e = parse_endpoint(options.bind);
  for (zmq::socket_t* s : {&impl_->publisher, &impl_->requests}) {
    s->set(zmq::sockopt::linger, 0);
    s->set(zmq::sockopt::heartbeat_ivl, options.heartbeat_ms);
    s->set(zmq::sockopt::heartbeat_timeout, 4 * options.heartbeat_ms);
    s->set(zmq::sockopt::heartbeat_ttl, 4 * options.heartbeat_ms);
  }
  if (options.curve) {
    std::array<std::uint8_t, 32> secret{};
    if (options.curve->secret_z85.size() != 40 ||
        zmq_z85_decode(secret.data(), options.curve->secret_z85.c_str()) == nullptr)
      throw std::runtime_error("the server's CURVE secret key is not 40 Z85 characters");
    impl_->zap = std::make_unique<ZapHandler>(impl_->context, options.curve->allowed_z85, options.log);
    for (zmq::socket_t* s : {&impl_->publisher, &impl_->requests}) {
      s->set(zmq::sockopt::curve_server, true);
      s->set(zmq::sockopt::curve_secretkey, zmq::buffer(secret));
      s->set(zmq::sockopt::zap_domain, "ddish");
    }
  }
  impl_->publisher.set(zmq::sockopt::sndhwm, std::max(1, options.send_hwm));
  impl_->requests.set(zmq::sockopt::router_mandatory, 0);
  for (auto [socket, address] : {std::pair{&impl_->publisher, e.publisher()},
                                 std::pair{&impl_->requests, e.requests()}}) {
    try {
      socket->bind(address);
    } catch (const zmq::error_t& err) {
      throw std::runtime_error("cannot bind " + address + ": " + err.what());
    }
  }
}

ProbeServer::~ProbeServer() = default;

void ProbeServer::publish(std::uint32_t brick, std::span<const std::uint8_t> frame) {
  const std::string topic = brick_topic(brick);
  try {
    std::array<zmq::const_buffer, 2> parts = {zmq::buffer(topic), zmq::buffer(frame.data(), frame.size())};
    if (zmq::send_multipart(impl_->publisher, parts, zmq::send_flags::dontwait))
      impl_->bytes += frame.size() + topic.size();
  } catch (const zmq::error_t& e) {
    if (e.num() != EINTR) throw;  // a signal (SIGINT, SIGTERM): the caller is about to stop
  }
}

double ProbeServer::serve_requests(int timeout_ms, const SnapshotFn& snapshot) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
  double busy_ms = 0.0;
  do {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        end - std::chrono::steady_clock::now());
    zmq::pollitem_t item{impl_->requests.handle(), 0, ZMQ_POLLIN, 0};
    try {
      zmq::poll(&item, 1, std::chrono::milliseconds(std::max<std::int64_t>(0, left.count())));
      const auto busy_start = std::chrono::steady_clock::now();
      while (true) {
        std::vector<zmq::message_t> parts;
        if (!zmq::recv_multipart(impl_->requests, std::back_inserter(parts), zmq::recv_flags::dontwait))
          break;
        impl_->handle(parts, snapshot);
      }
      busy_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - busy_start).count();
    } catch (const zmq::error_t& e) {
      if (e.num() != EINTR) throw;
      break;  // a signal (SIGINT, SIGTERM): let the caller look at it now
    }
  } while (std::chrono::steady_clock::now() < end);
  impl_->forget_silent_clients();
  return busy_ms;
}

std::vector<scene::View> ProbeServer::views() const {
  std::vector<scene::View> all;
  for (const auto& [id, c] : impl_->clients) all.insert(all.end(), c.views.begin(), c.views.end());
  return all;
}

std::size_t ProbeServer::clients() const { return impl_->clients.size(); }
std::uint64_t ProbeServer::bytes_published() const { return impl_->bytes; }
std::uint64_t ProbeServer::snapshots_sent() const { return impl_->snapshots; }
std::uint64_t ProbeServer::malformed_requests() const { return impl_->malformed; }
std::uint64_t ProbeServer::refused_keys() const { return impl_->zap ? impl_->zap->refused() : 0; }

}  // namespace ddish::net
