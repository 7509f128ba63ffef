#include "net/probe_client.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <stdexcept>
#include <set>

#include <fmt/format.h>
#include <zmq.hpp>
#include <zmq_addon.hpp>

#include "net/byte_io.h"
#include "net/endpoint.h"
#include "net/probe_mirror.h"
#include "net/probe_server.h"
#include "net/view_message.h"

namespace ddish::net {
namespace {

bool decode_key(const std::string& z85, std::array<std::uint8_t, 32>& out) {
  return z85.size() == 40 && zmq_z85_decode(out.data(), z85.c_str()) != nullptr;
}

}  // namespace

struct ProbeClient::Impl {
  ClientOptions options;
  Endpoint endpoint;
  probes::ProbeVolume& volume;
  std::uint64_t scene_id;
  ProbeMirror mirror;
  DecodeLimits limits;
  zmq::context_t context{1};
  zmq::socket_t subscriber{context, zmq::socket_type::sub};
  zmq::socket_t requests{context, zmq::socket_type::dealer};
  // The connection events of the subscription and of the request socket: a snapshot can come
  // back on the latter before the former has connected, so either one dropping is a loss.
  zmq::socket_t sub_events{context, zmq::socket_type::pair};
  zmq::socket_t request_events{context, zmq::socket_type::pair};
  std::int64_t last_message_us = 0;
  bool slow_logged = false;
  std::int64_t last_request_us = 0;
  bool lost = false;
  bool ever_synced = false;
  std::optional<std::int64_t> offset_us;  // server clock - client clock
  std::int64_t held_server_time_us = 0;   // trace end of the held frame, server clock
  std::uint64_t snapshots = 0, reconnects = 0;
  std::array<std::uint64_t, kRejectKindCount> rejects{};
  std::set<int> logged;

  Impl(const ClientOptions& o, probes::ProbeVolume& v, std::uint64_t id)
      : options(o), endpoint(parse_endpoint(o.connect)), volume(v), scene_id(id), mirror(v, id) {
    // A frame cannot hold more than the grid's probes: anything larger is a lie.
    const std::size_t n = std::size_t(v.probe_count());
    limits.max_payload_bytes = n * (5 + 1 + 152) + 64;
    for (zmq::socket_t* s : {&subscriber, &requests}) {
      s->set(zmq::sockopt::linger, 0);
      s->set(zmq::sockopt::heartbeat_ivl, o.heartbeat_ms);
      s->set(zmq::sockopt::heartbeat_timeout, 4 * o.heartbeat_ms);
      s->set(zmq::sockopt::heartbeat_ttl, 4 * o.heartbeat_ms);
      s->set(zmq::sockopt::reconnect_ivl, 100);
      // No back-off: a subscription still waiting out a long reconnect interval after the
      // snapshot came back on the request socket would look like a lost server again.
      s->set(zmq::sockopt::reconnect_ivl_max, 0);
    }
    if (o.curve) {
      std::array<std::uint8_t, 32> server{}, pub{}, secret{};
      if (!decode_key(o.curve->server_public_z85, server) || !decode_key(o.curve->public_z85, pub) ||
          !decode_key(o.curve->secret_z85, secret))
        throw std::runtime_error("a CURVE key of the client is not 40 Z85 characters");
      for (zmq::socket_t* s : {&subscriber, &requests}) {
        s->set(zmq::sockopt::curve_serverkey, zmq::buffer(server));
        s->set(zmq::sockopt::curve_publickey, zmq::buffer(pub));
        s->set(zmq::sockopt::curve_secretkey, zmq::buffer(secret));
      }
    }
    // Before connecting, so that the first connections' events are seen too.
    watch(subscriber, sub_events, "subscription");
    watch(requests, request_events, "requests");
    subscriber.set(zmq::sockopt::subscribe, "");
    requests.set(zmq::sockopt::immediate, 1);  // no requests queued for a dead connection
    subscriber.connect(endpoint.publisher());
    requests.connect(endpoint.requests());
  }

  void watch(zmq::socket_t& socket, zmq::socket_t& events, const char* what) {
    const std::string address = fmt::format("inproc://ddish-{}-{}", what, static_cast<void*>(this));
    if (zmq_socket_monitor(socket.handle(), address.c_str(),
                           ZMQ_EVENT_CONNECTED | ZMQ_EVENT_DISCONNECTED) != 0)
      throw zmq::error_t();
    events.set(zmq::sockopt::linger, 0);
    events.connect(address);
  }

  // Reads the connection events; true when a connection to the server dropped since the last
  // call.
  bool disconnected() {
    bool dropped = false;
    for (zmq::socket_t* events : {&sub_events, &request_events})
      while (true) {
        std::vector<zmq::message_t> parts;
        if (!zmq::recv_multipart(*events, std::back_inserter(parts), zmq::recv_flags::dontwait)) break;
        if (parts.empty() || parts[0].size() < 2) continue;
        std::uint16_t event = 0;
        std::memcpy(&event, parts[0].data(), 2);  // libzmq's event frame: u16 event, u32 value
        dropped |= event == ZMQ_EVENT_DISCONNECTED;
      }
    return dropped;
  }

  void log(const std::string& line) {
    if (options.log) options.log(line);
  }
  void count_reject(RejectKind kind, const std::string& detail) {
    ++rejects[std::size_t(kind)];
    if (logged.insert(int(kind)).second)
      log(kind == RejectKind::kSceneMismatch
              ? "refusing the probe server at " + options.connect + ": " + detail
              : "dropped a malformed probe message (" + reject_name(kind) + "): " + detail +
                    "; further ones are counted");
  }

  void request_snapshot(std::int64_t now) {
    if (now - last_request_us < std::int64_t(options.snapshot_retry_ms) * 1000) return;
    std::vector<std::uint8_t> t;
    ByteWriter(t).i64(now);
    std::array<zmq::const_buffer, 2> request = {zmq::str_buffer("SNAP"), zmq::buffer(t)};
    if (zmq::send_multipart(requests, request, zmq::send_flags::dontwait)) last_request_us = now;
  }

  // Decodes and applies one probe frame; true when it was applied.
  bool take(std::span<const std::uint8_t> bytes, ClientPoll& out) {
    DecodeResult r = decode_frame(bytes, limits);
    if (!r.ok) {
      count_reject(r.reject, r.detail);
      return false;
    }
    if (!mirror.matches(r.frame.header)) {
      const FrameHeader& h = r.frame.header;
      count_reject(RejectKind::kSceneMismatch,
                   fmt::format("it streams another scene or grid (identity {:016x}, grid {}x{}x{}, L{}; "
                               "this scene is {:016x}, grid {}x{}x{}, L{})",
                               h.scene_id, h.counts[0], h.counts[1], h.counts[2], h.sh_order, scene_id,
                               volume.grid().counts().x, volume.grid().counts().y,
                               volume.grid().counts().z, volume.sh_order()));
      return false;
    }
    std::vector<std::uint32_t> changed;
    const ApplyOutcome outcome = mirror.apply(r.frame, changed);
    if (outcome == ApplyOutcome::kGap) mirror.desync();  // lost a delta or a new server: re-snapshot
    if (outcome != ApplyOutcome::kApplied) return false;
    std::vector<std::uint32_t> merged;
    std::set_union(out.changed.begin(), out.changed.end(), changed.begin(), changed.end(),
                   std::back_inserter(merged));
    out.changed = std::move(merged);
    ++out.frames_applied;
    held_server_time_us = r.frame.header.server_time_us;
    if (r.frame.header.kind == FrameKind::kKeyframe) {
      ++out.keyframes_applied;
      ++snapshots;
      if (lost) {
        ++reconnects;
        log(fmt::format("probe server back at {}: snapshot of frame {} ({} probes; {} held ones kept "
                        "until it sends them)",
                        options.connect, r.frame.header.frame, r.frame.updated.size(), mirror.kept()));
      } else if (!ever_synced) {
        log(fmt::format("probes from {}: snapshot of frame {} ({} probes)", options.connect,
                        r.frame.header.frame, r.frame.updated.size()));
      }
      lost = false;
      ever_synced = true;
    }
    return true;
  }

  void receive(ClientPoll& out) {
    while (true) {
      zmq::message_t m;
      if (!subscriber.recv(m, zmq::recv_flags::dontwait)) break;
      last_message_us = steady_now_us();
      out.bytes += m.size();
      take({static_cast<const std::uint8_t*>(m.data()), m.size()}, out);
    }
    while (true) {
      std::vector<zmq::message_t> parts;
      if (!zmq::recv_multipart(requests, std::back_inserter(parts), zmq::recv_flags::dontwait)) break;
      const std::int64_t now = steady_now_us();
      last_message_us = now;
      for (const zmq::message_t& p : parts) out.bytes += p.size();
      if (parts.size() != 4 || parts[0].to_string() != "SNAP" || parts[1].size() != 8 ||
          parts[2].size() != 8) {
        count_reject(RejectKind::kSizeMismatch, "a snapshot reply of the wrong shape");
        continue;
      }
      std::int64_t sent = 0, server_now = 0;
      ByteReader({static_cast<const std::uint8_t*>(parts[1].data()), 8}).i64(sent);
      ByteReader({static_cast<const std::uint8_t*>(parts[2].data()), 8}).i64(server_now);
      if (sent > now || now - sent > 10'000'000) continue;  // not our request, or ancient
      if (take({static_cast<const std::uint8_t*>(parts[3].data()), parts[3].size()}, out))
        offset_us = server_now - (sent + now) / 2;
    }
  }
};

ProbeClient::ProbeClient(const ClientOptions& options, probes::ProbeVolume& volume,
                         std::uint64_t scene_id)
    : impl_(std::make_unique<Impl>(options, volume, scene_id)) {}

ProbeClient::~ProbeClient() = default;

ClientPoll ProbeClient::poll(int wait_ms) {
  ClientPoll out;
  try {
    poll_until(std::chrono::steady_clock::now() + std::chrono::milliseconds(wait_ms), out);
  } catch (const zmq::error_t& e) {
    // A signal (Ctrl-C, SIGTERM) can interrupt any ZeroMQ call, even a non-blocking one: the
    // frame goes on with what was received so far, and the caller looks at its stop flag.
    if (e.num() != EINTR) throw;
  }
  return out;
}

void ProbeClient::poll_until(std::chrono::steady_clock::time_point end, ClientPoll& out) {
  Impl& s = *impl_;
  while (true) {
    // What is queued first: a frame that took longer than stale_ms to render must not make a
    // live server look lost (the messages it sent meanwhile are waiting).
    s.receive(out);
    const std::int64_t now = steady_now_us();
    if (s.disconnected() && s.ever_synced && !s.lost) {
      s.lost = true;
      s.mirror.desync();
      s.log(fmt::format("lost the probe server at {}: rendering with the probes of frame {}",
                        s.options.connect, s.mirror.frame()));
    }
    const bool silent = s.last_message_us > 0 &&
                        now - s.last_message_us > std::int64_t(s.options.stale_ms) * 1000;
    if (silent && s.ever_synced && !s.lost && !s.slow_logged)
      s.log(fmt::format("no probes from {} for {} ms, the connection is up: the server is slow; "
                        "rendering with the probes of frame {}",
                        s.options.connect, (now - s.last_message_us) / 1000, s.mirror.frame()));
    s.slow_logged = silent;
    if (!s.mirror.synced()) {
      s.request_snapshot(now);
      s.receive(out);
    }
    if (out.frames_applied > 0 || std::chrono::steady_clock::now() >= end) break;
    std::array<zmq::pollitem_t, 2> items = {
        zmq::pollitem_t{s.subscriber.handle(), 0, ZMQ_POLLIN, 0},
        zmq::pollitem_t{s.requests.handle(), 0, ZMQ_POLLIN, 0}};
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        end - std::chrono::steady_clock::now());
    try {
      zmq::poll(items.data(), items.size(),
                std::chrono::milliseconds(std::clamp<std::int64_t>(left.count(), 0, s.options.snapshot_retry_ms)));
    } catch (const zmq::error_t& e) {
      if (e.num() != EINTR) throw;
      break;  // a signal: the frame goes on with what it has
    }
  }
}

void ProbeClient::send_views(const std::vector<scene::View>& views) {
  if (views.empty()) return;
  const std::vector<std::uint8_t> message = encode_views(views);
  std::array<zmq::const_buffer, 2> parts = {zmq::str_buffer("VIEW"), zmq::buffer(message)};
  try {
    zmq::send_multipart(impl_->requests, parts, zmq::send_flags::dontwait);
  } catch (const zmq::error_t& e) {
    if (e.num() != EINTR) throw;  // a signal: the views go with the next frame
  }
}

bool ProbeClient::synced() const { return impl_->mirror.synced(); }
bool ProbeClient::ever_synced() const { return impl_->ever_synced; }
std::uint64_t ProbeClient::server_frame() const { return impl_->mirror.frame(); }
double ProbeClient::stale_ms() const {
  return impl_->last_message_us > 0 ? double(steady_now_us() - impl_->last_message_us) / 1e3 : 0.0;
}
std::optional<double> ProbeClient::probe_age_ms() const {
  if (!impl_->offset_us || !impl_->ever_synced) return std::nullopt;
  return double(steady_now_us() - (impl_->held_server_time_us - *impl_->offset_us)) / 1e3;
}
std::uint64_t ProbeClient::snapshots() const { return impl_->snapshots; }
std::uint64_t ProbeClient::reconnects() const { return impl_->reconnects; }
std::uint64_t ProbeClient::rejected(RejectKind kind) const { return impl_->rejects[std::size_t(kind)]; }
std::uint64_t ProbeClient::rejected_total() const {
  std::uint64_t n = 0;
  for (std::uint64_t r : impl_->rejects) n += r;
  return n;
}

}  // namespace ddish::net
