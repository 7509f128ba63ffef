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

#include "net/bricks.h"
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

std::span<const std::uint8_t> bytes_of(const zmq::message_t& m) {
  return {static_cast<const std::uint8_t*>(m.data()), m.size()};
}

// ZeroMQ options every client socket shares: heartbeats, and reconnection every 100 ms with no
// back-off (a subscription still waiting out a long reconnect interval after the snapshot came
// back on the request socket would look like a lost server again).
void set_common(zmq::socket_t& s, const ClientOptions& o, bool curve) {
  s.set(zmq::sockopt::linger, 0);
  s.set(zmq::sockopt::heartbeat_ivl, o.heartbeat_ms);
  s.set(zmq::sockopt::heartbeat_timeout, 4 * o.heartbeat_ms);
  s.set(zmq::sockopt::heartbeat_ttl, 4 * o.heartbeat_ms);
  s.set(zmq::sockopt::reconnect_ivl, 100);
  s.set(zmq::sockopt::reconnect_ivl_max, 0);
  if (o.curve && curve) {
    std::array<std::uint8_t, 32> server{}, pub{}, secret{};
    if (!decode_key(o.curve->server_public_z85, server) || !decode_key(o.curve->public_z85, pub) ||
        !decode_key(o.curve->secret_z85, secret))
      throw std::runtime_error("a CURVE key of the client is not 40 Z85 characters");
    s.set(zmq::sockopt::curve_serverkey, zmq::buffer(server));
    s.set(zmq::sockopt::curve_publickey, zmq::buffer(pub));
    s.set(zmq::sockopt::curve_secretkey, zmq::buffer(secret));
  }
}

// Watches a socket's connections through libzmq's monitor (an inproc PAIR).
void watch(zmq::socket_t& socket, zmq::socket_t& events, const void* owner, const std::string& what) {
  const std::string address = fmt::format("inproc://ddish-{}-{}", what, owner);
  if (zmq_socket_monitor(socket.handle(), address.c_str(), ZMQ_EVENT_CONNECTED | ZMQ_EVENT_DISCONNECTED) != 0)
    throw zmq::error_t();
  events.set(zmq::sockopt::linger, 0);
  events.connect(address);
}

// The endpoints whose connection dropped since the last call.
std::vector<std::string> dropped_endpoints(zmq::socket_t& events) {
  std::vector<std::string> dropped;
  while (true) {
    std::vector<zmq::message_t> parts;
    if (!zmq::recv_multipart(events, std::back_inserter(parts), zmq::recv_flags::dontwait)) break;
    if (parts.size() < 2 || parts[0].size() < 2) continue;
    std::uint16_t event = 0;
    std::memcpy(&event, parts[0].data(), 2);  // libzmq's event frame: u16 event, u32 value
    if (event == ZMQ_EVENT_DISCONNECTED) dropped.push_back(parts[1].to_string());
  }
  return dropped;
}

}  // namespace

std::optional<StreamDescription> ask_stream_description(const ClientOptions& options, int wait_ms,
                                                        std::string* problem) {
  zmq::context_t context(1);
  std::vector<zmq::socket_t> sockets;
  std::string why = fmt::format("no answer within {} ms", wait_ms);
  try {
    for (const Endpoint& e : parse_endpoint_list(options.connect)) {
      zmq::socket_t& s = sockets.emplace_back(context, zmq::socket_type::dealer);
      set_common(s, options, true);
      s.connect(e.requests());
      s.send(zmq::str_buffer("INFO"), zmq::send_flags::dontwait);  // queued until connected
    }
    const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(wait_ms);
    std::size_t answers = 0;  // refused ones: once every server has answered, waiting is no use
    while (answers < sockets.size()) {
      std::vector<zmq::pollitem_t> items;
      for (zmq::socket_t& s : sockets) items.push_back({s.handle(), 0, ZMQ_POLLIN, 0});
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - std::chrono::steady_clock::now());
      if (left.count() <= 0) break;
      zmq::poll(items.data(), items.size(), left);
      for (zmq::socket_t& s : sockets) {
        std::vector<zmq::message_t> parts;
        if (!zmq::recv_multipart(s, std::back_inserter(parts), zmq::recv_flags::dontwait)) continue;
        ++answers;
        if ((parts.size() != 2 && parts.size() != 3) || parts[0].to_string() != "INFO") {
          why = "an INFO reply of the wrong shape";
          continue;
        }
        DecodeLimits empty;  // the description holds no probes: nothing to inflate
        empty.max_payload_bytes = 0;
        const DecodeResult r = decode_frame(bytes_of(parts[1]), empty);
        if (!r.ok || r.frame.header.kind != FrameKind::kKeyframe || !r.frame.updated.empty()) {
          why = r.ok ? "an INFO reply that is not an empty keyframe" : reject_name(r.reject) + ": " + r.detail;
          continue;
        }
        StreamDescription d{r.frame.header, std::nullopt};
        if (parts.size() == 3) {
          scene::Aabb b;
          if (!decode_grid_bounds(bytes_of(parts[2]), b)) {
            why = fmt::format("grid bounds of {} bytes in an INFO reply, not 6 finite ordered floats", parts[2].size());
            continue;
          }
          d.bounds = b;
        }
        return d;
      }
    }
  } catch (const zmq::error_t& e) {
    if (e.num() != EINTR) throw;
    why = "interrupted";
  }
  if (problem) *problem = why;
  return std::nullopt;
}

struct ProbeClient::Impl {
  // One server: its request socket and its clocks.
  struct Server {
    Endpoint endpoint;
    std::string address;
    zmq::socket_t requests;
    zmq::socket_t events;  // the request socket's connection events
    bool lost = false;
    bool ever_synced = false;
    std::int64_t last_request_us = 0;
    std::optional<std::int64_t> offset_us;  // server clock - client clock
  };
  ClientOptions options;
  probes::ProbeVolume& volume;
  std::uint64_t scene_id;
  BrickLayout layout;
  float margin;
  DecodeLimits limits;
  zmq::context_t context{1};
  std::vector<std::unique_ptr<Server>> servers;
  zmq::socket_t subscriber{context, zmq::socket_type::sub};
  zmq::socket_t sub_events{context, zmq::socket_type::pair};
  // Per brick: its mirror (made when first subscribed), the server of its last keyframe (-1:
  // none), whether it is subscribed, frames received.
  std::vector<std::unique_ptr<ProbeMirror>> mirrors;
  std::vector<int> brick_server;
  std::vector<std::uint8_t> subscribed;
  std::vector<std::uint64_t> frames_received;
  std::int64_t last_message_us = 0;
  bool slow_logged = false;
  std::int64_t held_server_time_us = 0;  // trace end of the newest frame applied, its server's clock
  int held_server = -1;
  std::uint64_t snapshots = 0, reconnects = 0;
  std::array<std::uint64_t, kRejectKindCount> rejects{};
  std::set<int> logged;

  Impl(const ClientOptions& o, probes::ProbeVolume& v, std::uint64_t id)
      : options(o), volume(v), scene_id(id), layout(v.grid()) {
    const glm::vec3 spacing = v.grid().spacing();
    // The bricks' boxes already reach one cell past their probes; a quarter cell more covers a
    // camera's step before its next subscription takes effect.
    margin = 0.25f * std::max({spacing.x, spacing.y, spacing.z});
    // A frame cannot hold more than a brick's probes: anything larger is a lie.
    // (per probe: 3 index varints, a flag byte, the largest record and an offset).
    limits.max_payload_bytes =
        std::size_t(kBrickEdge * kBrickEdge * kBrickEdge) *
            (3 * 5 + 1 + 152 + moment_bytes(kMaxWireMomentResolution * kMaxWireMomentResolution) + 12) +
        64;
    const std::vector<Endpoint> endpoints = parse_endpoint_list(o.connect);
    std::optional<Endpoint> relay;
    if (!o.relay.empty()) relay = parse_endpoint(o.relay);
    // Eight ticks of every brick queue before ZeroMQ drops (then the client re-snapshots).
    subscriber.set(zmq::sockopt::rcvhwm, int(std::max<std::uint32_t>(1000, 8 * layout.brick_count())));
    set_common(subscriber, o, !relay);  // a relay speaks plaintext (it binds loopback unless told otherwise)
    watch(subscriber, sub_events, this, "subscription");
    const std::uint32_t bricks = layout.brick_count();
    mirrors.resize(bricks);
    brick_server.assign(bricks, -1);
    subscribed.assign(bricks, 0);
    frames_received.assign(bricks, 0);
    subscribe(layout.needed(o.views, margin));  // before connecting: the Clone pattern subscribes first
    for (const Endpoint& e : endpoints) {
      auto s = std::make_unique<Server>(Server{e, e.publisher(), zmq::socket_t(context, zmq::socket_type::dealer),
                                               zmq::socket_t(context, zmq::socket_type::pair)});
      set_common(s->requests, o, true);
      watch(s->requests, s->events, s.get(), "requests");
      s->requests.set(zmq::sockopt::immediate, 1);  // no requests queued for a dead connection
      s->requests.connect(e.requests());
      if (!relay) subscriber.connect(e.publisher());
      servers.push_back(std::move(s));
    }
    if (relay) subscriber.connect(relay->publisher());
  }

  void subscribe(const std::vector<std::uint32_t>& needed) {
    std::vector<std::uint8_t> want(subscribed.size(), 0);
    for (std::uint32_t b : needed) want[b] = 1;
    for (std::uint32_t b = 0; b < want.size(); ++b) {
      if (want[b] == subscribed[b]) continue;
      const std::string topic = brick_topic(b);
      if (want[b]) {
        if (!mirrors[b]) mirrors[b] = std::make_unique<ProbeMirror>(volume, scene_id, layout.probes(b));
        subscriber.set(zmq::sockopt::subscribe, topic);
      } else {
        subscriber.set(zmq::sockopt::unsubscribe, topic);
        mirrors[b]->desync();  // its probes stay; a snapshot when it is needed again
      }
      subscribed[b] = want[b];
    }
  }

  std::vector<std::uint32_t> unsynced() const {
    std::vector<std::uint32_t> out;
    for (std::uint32_t b = 0; b < subscribed.size(); ++b)
      if (subscribed[b] && !mirrors[b]->synced()) out.push_back(b);
    return out;
  }
  std::uint64_t newest_frame(int server) const {
    std::uint64_t f = 0;
    for (std::uint32_t b = 0; b < mirrors.size(); ++b)
      if (mirrors[b] && (server < 0 || brick_server[b] == server)) f = std::max(f, mirrors[b]->frame());
    return f;
  }

  void log(const std::string& line) {
    if (options.log) options.log(line);
  }
  void count_reject(RejectKind kind, const std::string& detail, const std::string& from) {
    ++rejects[std::size_t(kind)];
    if (!logged.insert(int(kind)).second) return;
    if (kind == RejectKind::kSceneMismatch)
      log("refusing the probe server at " + from + ": " + detail);
    else if (kind == RejectKind::kBadVersion)
      log("refusing the probe server at " + from + ": it speaks another version of the probe stream (" +
          detail + "); run the same ddish release on both sides");
    else
      log("dropped a malformed probe message (" + reject_name(kind) + "): " + detail +
          "; further ones are counted");
  }

  void request_snapshots(std::int64_t now) {
    const std::vector<std::uint32_t> wanted = unsynced();
    if (wanted.empty()) return;
    std::vector<std::uint8_t> t, bricks;
    ByteWriter(t).i64(now);
    ByteWriter w(bricks);
    for (std::uint32_t b : wanted) w.u32(b);
    for (auto& s : servers) {
      if (now - s->last_request_us < std::int64_t(options.snapshot_retry_ms) * 1000) continue;
      std::array<zmq::const_buffer, 3> request = {zmq::str_buffer("SNAP"), zmq::buffer(t), zmq::buffer(bricks)};
      if (zmq::send_multipart(s->requests, request, zmq::send_flags::dontwait)) s->last_request_us = now;
    }
  }

  // Decodes and applies one frame of `brick` (`server`: the one it came from, -1 when the
  // subscription carried it); true when it was applied. `probes`, `kept`: a keyframe's counts.
  bool take(std::uint32_t brick, std::span<const std::uint8_t> bytes, int server, const std::string& from,
            ClientPoll& out, std::size_t* probes = nullptr, std::size_t* kept = nullptr) {
    ++frames_received[brick];
    DecodeResult r = decode_frame(bytes, limits);
    if (!r.ok) {
      count_reject(r.reject, r.detail, from);
      return false;
    }
    ProbeMirror& mirror = *mirrors[brick];
    if (!mirror.matches(r.frame.header)) {
      const FrameHeader& h = r.frame.header;
      const bool same_scene = h.scene_id == scene_id && h.sh_order == volume.sh_order() &&
                              h.counts[0] == std::uint32_t(volume.grid().counts().x) &&
                              h.counts[1] == std::uint32_t(volume.grid().counts().y) &&
                              h.counts[2] == std::uint32_t(volume.grid().counts().z);
      const auto maps = [](int resolution, float range) {
        return resolution > 0 ? fmt::format("{0}x{0} distance-moment maps over {1:g} m", resolution, range)
                              : std::string("no distance moments");
      };
      if (same_scene)
        count_reject(RejectKind::kSceneMismatch,
                     fmt::format("its probes carry {}, this client's volume {} (a client sizes its maps by "
                                 "the server that answers as it starts: restart it while the server is up)",
                                 maps(h.moment_resolution, h.moment_range),
                                 maps(volume.moment_resolution(), volume.moment_range())),
                     from);
      else
        count_reject(RejectKind::kSceneMismatch,
                     fmt::format("it streams another scene or grid (identity {:016x}, grid {}x{}x{}, L{}; "
                                 "this scene is {:016x}, grid {}x{}x{}, L{})",
                                 h.scene_id, h.counts[0], h.counts[1], h.counts[2], h.sh_order, scene_id,
                                 volume.grid().counts().x, volume.grid().counts().y,
                                 volume.grid().counts().z, volume.sh_order()),
                     from);
      return false;
    }
    const bool keyframe = r.frame.header.kind == FrameKind::kKeyframe;
    if (keyframe && server < 0) {
      count_reject(RejectKind::kBadHeader, "a keyframe on the subscription (snapshots come on requests)", from);
      return false;
    }
    std::vector<std::uint32_t> changed;
    const ApplyOutcome outcome = mirror.apply(r.frame, changed);
    if (outcome == ApplyOutcome::kOutside) {
      count_reject(RejectKind::kBadIndex, fmt::format("probes outside brick {} under its topic", brick), from);
      return false;
    }
    if (outcome == ApplyOutcome::kBadOffset) {
      count_reject(RejectKind::kBadVisibility,
                   fmt::format("a relocation offset beyond {:g} of a cell", probes::kMaxRelocation), from);
      return false;
    }
    if (outcome == ApplyOutcome::kGap) mirror.desync();  // lost a delta or a new server: re-snapshot
    if (outcome != ApplyOutcome::kApplied) return false;
    std::vector<std::uint32_t> merged;
    std::set_union(out.changed.begin(), out.changed.end(), changed.begin(), changed.end(),
                   std::back_inserter(merged));
    out.changed = std::move(merged);
    ++out.frames_applied;
    if (keyframe) brick_server[brick] = server;
    held_server_time_us = r.frame.header.server_time_us;
    held_server = brick_server[brick];
    if (keyframe) {
      ++out.keyframes_applied;
      ++snapshots;
      if (probes) *probes += r.frame.updated.size();
      if (kept) *kept += mirror.kept();
    }
    return true;
  }

  void receive_subscription(ClientPoll& out) {
    const std::string from = options.relay.empty() ? options.connect : options.relay;
    while (true) {
      std::vector<zmq::message_t> parts;
      if (!zmq::recv_multipart(subscriber, std::back_inserter(parts), zmq::recv_flags::dontwait)) break;
      last_message_us = steady_now_us();
      for (const zmq::message_t& p : parts) out.bytes += p.size();
      if (parts.size() != 2) {
        count_reject(RejectKind::kSizeMismatch, "a probe message not of two parts (topic, frame)", from);
        continue;
      }
      const std::optional<std::uint32_t> brick = parse_brick_topic(bytes_of(parts[0]));
      if (!brick || *brick >= subscribed.size()) {
        count_reject(RejectKind::kBadHeader, "a topic that names no brick of this grid", from);
        continue;
      }
      if (!subscribed[*brick]) {
        ++frames_received[*brick];
        continue;  // sent before our unsubscription reached the server
      }
      take(*brick, bytes_of(parts[1]), -1, from, out);
    }
  }

  void receive_replies(int index, ClientPoll& out) {
    Server& s = *servers[std::size_t(index)];
    while (true) {
      std::vector<zmq::message_t> parts;
      if (!zmq::recv_multipart(s.requests, std::back_inserter(parts), zmq::recv_flags::dontwait)) break;
      const std::int64_t now = steady_now_us();
      last_message_us = now;
      for (const zmq::message_t& p : parts) out.bytes += p.size();
      if (parts.size() < 3 || (parts.size() - 3) % 2 != 0 || parts[0].to_string() != "SNAP" ||
          parts[1].size() != 8 || parts[2].size() != 8) {
        count_reject(RejectKind::kSizeMismatch, "a snapshot reply of the wrong shape", s.address);
        continue;
      }
      std::int64_t sent = 0, server_now = 0;
      ByteReader(bytes_of(parts[1])).i64(sent);
      ByteReader(bytes_of(parts[2])).i64(server_now);
      if (sent > now || now - sent > 10'000'000) continue;  // not our request, or ancient
      s.offset_us = server_now - (sent + now) / 2;
      std::size_t applied = 0, probes = 0, kept = 0;
      std::uint64_t frame = 0;
      for (std::size_t k = 3; k < parts.size(); k += 2) {
        const std::optional<std::uint32_t> brick = parse_brick_topic(bytes_of(parts[k]));
        if (!brick || *brick >= subscribed.size()) {
          count_reject(RejectKind::kBadHeader, "a snapshot of a topic that names no brick of this grid", s.address);
          continue;
        }
        if (!subscribed[*brick]) continue;
        if (take(*brick, bytes_of(parts[k + 1]), index, s.address, out, &probes, &kept)) {
          ++applied;
          frame = std::max(frame, mirrors[*brick]->frame());
        }
      }
      if (applied == 0) continue;
      if (s.lost) {
        ++reconnects;
        log(fmt::format("probe server back at {}: snapshot of frame {} ({} probes; {} held ones kept "
                        "until it sends them)",
                        s.address, frame, probes, kept));
      } else if (!s.ever_synced) {
        log(fmt::format("probes from {}: snapshot of frame {} ({} probes)", s.address, frame, probes));
      }
      s.lost = false;
      s.ever_synced = true;
    }
  }

  void receive(ClientPoll& out) {
    receive_subscription(out);
    for (int k = 0; k < int(servers.size()); ++k) receive_replies(k, out);
  }

  void lose(int index) {
    Server& s = *servers[std::size_t(index)];
    if (!s.ever_synced || s.lost) return;
    s.lost = true;
    for (std::uint32_t b = 0; b < mirrors.size(); ++b)
      if (mirrors[b] && brick_server[b] == index) mirrors[b]->desync();
    log(fmt::format("lost the probe server at {}: rendering with the probes of frame {}", s.address,
                    newest_frame(index)));
  }

  // Connections that dropped: a server's request socket, or its subscription (direct), or the
  // relay's (then every server's frames are gone).
  void check_connections() {
    const std::vector<std::string> sub_dropped = dropped_endpoints(sub_events);
    for (int k = 0; k < int(servers.size()); ++k) {
      bool dropped = !dropped_endpoints(servers[std::size_t(k)]->events).empty();
      for (const std::string& e : sub_dropped)
        dropped |= !options.relay.empty() || e == servers[std::size_t(k)]->endpoint.publisher();
      if (dropped) lose(k);
    }
  }
};

ProbeClient::ProbeClient(const ClientOptions& options, probes::ProbeVolume& volume,
                         std::uint64_t scene_id)
    : impl_(std::make_unique<Impl>(options, volume, scene_id)) {}

ProbeClient::~ProbeClient() = default;

ClientPoll ProbeClient::poll(int wait_ms, bool until_synced) {
  ClientPoll out;
  try {
    poll_until(std::chrono::steady_clock::now() + std::chrono::milliseconds(wait_ms), until_synced, out);
  } catch (const zmq::error_t& e) {
    // A signal (Ctrl-C, SIGTERM) can interrupt any ZeroMQ call, even a non-blocking one: the
    // frame goes on with what was received so far, and the caller looks at its stop flag.
    if (e.num() != EINTR) throw;
  }
  return out;
}

void ProbeClient::poll_until(std::chrono::steady_clock::time_point end, bool until_synced, ClientPoll& out) {
  Impl& s = *impl_;
  while (true) {
    // What is queued first: a frame that took longer than stale_ms to render must not make a
    // live server look lost (the messages it sent meanwhile are waiting).
    s.receive(out);
    const std::int64_t now = steady_now_us();
    s.check_connections();
    const bool silent = s.last_message_us > 0 &&
                        now - s.last_message_us > std::int64_t(s.options.stale_ms) * 1000;
    bool any_live = false;
    for (const auto& server : s.servers) any_live |= server->ever_synced && !server->lost;
    if (silent && any_live && !s.slow_logged)
      s.log(fmt::format("no probes from {} for {} ms, the connection is up: the server is slow; "
                        "rendering with the probes of frame {}",
                        s.options.connect, (now - s.last_message_us) / 1000, s.newest_frame(-1)));
    s.slow_logged = silent;
    if (!synced()) {
      s.request_snapshots(now);
      s.receive(out);
    }
    if ((out.frames_applied > 0 && (!until_synced || synced())) || std::chrono::steady_clock::now() >= end) break;
    std::vector<zmq::pollitem_t> items = {zmq::pollitem_t{s.subscriber.handle(), 0, ZMQ_POLLIN, 0}};
    for (const auto& server : s.servers) items.push_back({server->requests.handle(), 0, ZMQ_POLLIN, 0});
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
  impl_->subscribe(impl_->layout.needed(views, impl_->margin));
  const std::vector<std::uint8_t> message = encode_views(views);
  std::array<zmq::const_buffer, 2> parts = {zmq::str_buffer("VIEW"), zmq::buffer(message)};
  try {
    for (auto& s : impl_->servers) zmq::send_multipart(s->requests, parts, zmq::send_flags::dontwait);
  } catch (const zmq::error_t& e) {
    if (e.num() != EINTR) throw;  // a signal: the views go with the next frame
  }
}

bool ProbeClient::synced() const {
  bool any = false;
  for (std::uint32_t b = 0; b < impl_->subscribed.size(); ++b)
    if (impl_->subscribed[b]) {
      if (!impl_->mirrors[b]->synced()) return false;
      any = true;
    }
  return any;
}
bool ProbeClient::ever_synced() const {
  for (const auto& s : impl_->servers)
    if (s->ever_synced) return true;
  return false;
}
std::uint64_t ProbeClient::server_frame() const { return impl_->newest_frame(-1); }
std::vector<std::uint32_t> ProbeClient::subscribed_bricks() const {
  std::vector<std::uint32_t> out;
  for (std::uint32_t b = 0; b < impl_->subscribed.size(); ++b)
    if (impl_->subscribed[b]) out.push_back(b);
  return out;
}
std::vector<std::uint64_t> ProbeClient::frames_per_brick() const { return impl_->frames_received; }
double ProbeClient::stale_ms() const {
  return impl_->last_message_us > 0 ? double(steady_now_us() - impl_->last_message_us) / 1e3 : 0.0;
}
std::optional<double> ProbeClient::probe_age_ms() const {
  const Impl& s = *impl_;
  if (s.held_server < 0 || !s.servers[std::size_t(s.held_server)]->offset_us) return std::nullopt;
  return double(steady_now_us() - (s.held_server_time_us - *s.servers[std::size_t(s.held_server)]->offset_us)) / 1e3;
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
