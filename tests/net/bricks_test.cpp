// Past one server: the probe grid cut into bricks (net/bricks.h) owned by two servers, eight
// clients that subscribe only to the bricks their views need, four of them through a relay
// (net/relay.h, a zmq_proxy XSUB/XPUB forwarder) and four directly; one server lost and
// restarted while the other goes on. On loopback, in one process taking turns (the relay
// forwards in its own thread); every wait is bounded by a turn count.
#include <unistd.h>

#include <atomic>
#include <memory>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <zmq.hpp>
#include <zmq_addon.hpp>

#include "net/bricks.h"
#include "net/probe_client.h"
#include "net/probe_server.h"
#include "net/published_probes.h"
#include "net/relay.h"
#include "net_test_util.h"

namespace ddish::net {
namespace {

constexpr std::uint64_t kScene = 0xb1c;

// Ports per test process, below Linux's ephemeral range (tests/net/transport_test.cpp says why)
// and apart from the transport tests' 20000-32000.
int base_port() { return 16000 + int(getpid() % 500) * 8; }
std::string address(int k) { return "tcp://127.0.0.1:" + std::to_string(base_port() + 2 * k); }

// 8 x 4 x 4 probes over [0,4] x [0,2] x [0,2]: two bricks, x < 4 and x >= 4.
probes::ProbeGrid grid() { return probes::ProbeGrid(scene::Aabb{glm::vec3(0.0f), glm::vec3(4.0f, 2.0f, 2.0f)}, {8, 4, 4}); }

// What probe i holds after update `frame`: the same on every server (as a probe tracer's
// per-probe sampler streams make it), so a client of two servers can be compared with one of a
// single server.
sh::ShRgb probe_at(std::uint32_t i, std::uint64_t frame) {
  std::mt19937_64 rng(i * 7919u + frame);
  return test::radiance_probe(rng, 2, 1.0f + 0.01f * float(frame));
}

// A server of share `share` of 2 (or of everything): one published stream per owned brick.
struct BrickServer {
  BrickLayout layout{grid()};
  BrickShare share;
  probes::ProbeVolume volume{grid(), 2};
  std::vector<std::uint32_t> owned;
  std::vector<PublishedProbes> streams;
  ProbeServer server;
  std::uint64_t frame = 0;

  BrickServer(const std::string& bind, BrickShare s, std::uint64_t stream)
      : share(s), server({.bind = bind, .client_timeout_ms = 500}) {
    for (std::uint32_t b = 0; b < layout.brick_count(); ++b)
      if (share.owns(b)) {
        owned.push_back(b);
        streams.emplace_back(volume, kScene, stream, StreamOptions{.encoding = Encoding::kHalf}, layout.probes(b));
      }
  }
  void tick(int ms) {
    ++frame;
    for (std::uint32_t b : owned)
      for (std::uint32_t i : layout.probes(b)) {
        volume.set_sh(i, probe_at(i, frame));
        volume.state(i).flags = 0;
        volume.state(i).updates += 1;
      }
    for (std::size_t k = 0; k < owned.size(); ++k)
      server.publish(owned[k], streams[k].publish(volume, frame, steady_now_us(), 0.0));
    server.serve_requests(ms, [&](std::uint32_t brick) {
      for (std::size_t k = 0; k < owned.size(); ++k)
        if (owned[k] == brick) return streams[k].snapshot();
      return std::vector<std::uint8_t>{};
    });
  }
};

// Views that need brick 0 only (looking down -x from x = 0.8), brick 1 only (down +x from
// x = 3.2), or both (across the middle).
scene::View view_of(int bricks) {
  if (bricks == 0) return scene::look_at_view({0.8f, 1, 1}, {-1, 1, 1}, {0, 1, 0}, 1.0f, 32, 32);
  if (bricks == 1) return scene::look_at_view({3.2f, 1, 1}, {5, 1, 1}, {0, 1, 0}, 1.0f, 32, 32);
  return scene::look_at_view({2, 1, -3}, {2, 1, 1}, {0, 1, 0}, 1.0f, 32, 32);
}

ClientOptions client_options(const std::string& connect, const std::string& relay, int bricks,
                             std::vector<std::string>* log) {
  ClientOptions o;
  o.connect = connect;
  o.relay = relay;
  o.stale_ms = 300;
  o.snapshot_retry_ms = 50;
  o.views = {view_of(bricks)};
  o.log = [log](const std::string& line) { log->push_back(line); };
  return o;
}

// Whether the client's probes of `brick` are the servers' of `frame` (fp16 on the wire).
bool holds(const probes::ProbeVolume& v, std::uint32_t brick, std::uint64_t frame) {
  for (std::uint32_t i : BrickLayout(grid()).probes(brick)) {
    const sh::ShRgb want = probe_at(i, frame);
    for (std::size_t j = 0; j < 9; ++j)
      for (int c = 0; c < 3; ++c)
        if (std::fabs(v.coefficients(i)[j][c] - want[j][c]) > std::fabs(want[j][c]) * 0x1p-11f + 1e-6f) return false;
    if (!v.state(i).active()) return false;
  }
  return true;
}
bool untouched(const probes::ProbeVolume& v, std::uint32_t brick) {
  for (std::uint32_t i : BrickLayout(grid()).probes(brick))
    if (v.coefficients(i)[0] != glm::vec3(0.0f) || v.state(i).updates != 0) return false;
  return true;
}

TEST(Bricks, LayoutTopicsAndShares) {
  const BrickLayout layout(grid());
  ASSERT_EQ(layout.brick_count(), 2u);
  EXPECT_EQ(layout.probes(0).size(), 64u);
  EXPECT_EQ(layout.probes(1).front(), 4u);  // cell (4, 0, 0)
  for (std::uint32_t b = 0; b < 2; ++b)
    for (std::uint32_t i : layout.probes(b)) EXPECT_EQ(layout.brick_of(i), b);
  // 10 x 5 x 1 probes: 3 x 2 x 1 bricks, the far ones smaller; together every probe once.
  const BrickLayout odd(probes::ProbeGrid(scene::Aabb{glm::vec3(0.0f), glm::vec3(1.0f)}, {10, 5, 1}));
  ASSERT_EQ(odd.brick_count(), 6u);
  std::size_t total = 0;
  for (std::uint32_t b = 0; b < 6; ++b) total += odd.probes(b).size();
  EXPECT_EQ(total, 50u);
  EXPECT_EQ(odd.probes(5).size(), 2u);  // x 8..9, y 4
  EXPECT_EQ(brick_topic(42), "b0000002a");
  const std::string t = brick_topic(42);
  EXPECT_EQ(parse_brick_topic({reinterpret_cast<const std::uint8_t*>(t.data()), t.size()}), 42u);
  for (const std::string bad : {"b0000002A", "b000002a", "c0000002a", "b0000002a0", "b00000g2a"})
    EXPECT_FALSE(parse_brick_topic({reinterpret_cast<const std::uint8_t*>(bad.data()), bad.size()})) << bad;
  EXPECT_EQ(parse_brick_share("1/3").index, 1u);
  EXPECT_TRUE(parse_brick_share("2/3").owns(5));
  for (const char* bad : {"3/3", "1", "/2", "1/0", "a/2", "1/2x", "0/5000"})
    EXPECT_THROW(parse_brick_share(bad), std::invalid_argument) << bad;
  EXPECT_EQ(layout.needed(std::vector{view_of(0)}, 0.67f), std::vector<std::uint32_t>{0});
  EXPECT_EQ(layout.needed(std::vector{view_of(1)}, 0.67f), std::vector<std::uint32_t>{1});
  EXPECT_EQ(layout.needed(std::vector{view_of(2)}, 0.67f), (std::vector<std::uint32_t>{0, 1}));
  EXPECT_EQ(layout.needed(std::vector<scene::View>{}, 0.67f), (std::vector<std::uint32_t>{0, 1}));
}

// Two servers (bricks 0/2 and 1/2), a relay, eight clients: 0-3 through the relay, all needing
// brick 0 only; 4-5 direct, brick 1 only; 6-7 direct, both. Each client gets exactly the
// frames of its bricks (one per tick, none of the others), and holds exactly what one server of
// the whole grid would have sent; the relay passes one subscription upstream for its four
// clients.
TEST(Bricks, TwoServersEightClientsGetExactlyTheirBricks) {
  BrickServer s0(address(0), {0, 2}, 11), s1(address(1), {1, 2}, 12);
  const std::string servers = address(0) + "," + address(1);
  auto relay = std::make_unique<Relay>(RelayOptions{.upstream = {address(0), address(1)}, .bind = address(2)});
  std::atomic<bool> stop{false};
  RelayStats relay_stats;
  std::thread relay_thread([&] { relay_stats = relay->run([&] { return stop.load(); }); });

  const int needs[8] = {0, 0, 0, 0, 1, 1, 2, 2};
  std::vector<std::vector<std::string>> logs(8);
  std::vector<std::unique_ptr<probes::ProbeVolume>> volumes;
  std::vector<std::unique_ptr<ProbeClient>> clients;
  for (int c = 0; c < 8; ++c) {
    volumes.push_back(std::make_unique<probes::ProbeVolume>(grid(), 2));
    clients.push_back(std::make_unique<ProbeClient>(
        client_options(servers, c < 4 ? address(2) : "", needs[c], &logs[std::size_t(c)]), *volumes.back(), kScene));
  }
  const auto turn = [&](int ms) {
    s0.tick(ms);
    s1.tick(ms);
    for (auto& c : clients) c->poll(2);
  };
  const auto all_at = [&](std::uint64_t frame) {  // every client holds this frame of each brick it needs
    for (int c = 0; c < 8; ++c) {
      if (!clients[std::size_t(c)]->synced()) return false;
      for (std::uint32_t b = 0; b < 2; ++b)
        if ((needs[c] == 2 || needs[c] == int(b)) && !holds(*volumes[std::size_t(c)], b, frame)) return false;
    }
    return true;
  };
  for (int k = 0; k < 300 && !all_at(s0.frame); ++k) turn(5);
  ASSERT_TRUE(all_at(s0.frame)) << "not every client synced";
  // Ten more ticks, each followed until every client holds it: one delta per needed brick each.
  std::vector<std::vector<std::uint64_t>> before;
  for (auto& c : clients) before.push_back(c->frames_per_brick());
  const int ticks = 10;
  for (int k = 0; k < ticks; ++k) {
    turn(2);
    for (int w = 0; w < 100 && !all_at(s0.frame); ++w)
      for (auto& c : clients) c->poll(2);
    ASSERT_TRUE(all_at(s0.frame)) << "tick " << k;
  }
  for (int c = 0; c < 8; ++c) {
    const std::vector<std::uint32_t> want = needs[c] == 2 ? std::vector<std::uint32_t>{0, 1}
                                                          : std::vector<std::uint32_t>{std::uint32_t(needs[c])};
    EXPECT_EQ(clients[std::size_t(c)]->subscribed_bricks(), want) << "client " << c;
    const std::vector<std::uint64_t> after = clients[std::size_t(c)]->frames_per_brick();
    std::uint32_t held = 0;
    for (std::uint32_t b = 0; b < 2; ++b) {
      const bool needed = needs[c] == 2 || needs[c] == int(b);
      if (needed) {
        EXPECT_EQ(after[b] - before[std::size_t(c)][b], std::uint64_t(ticks)) << "client " << c << " brick " << b;
        EXPECT_TRUE(holds(*volumes[std::size_t(c)], b, s0.frame)) << "client " << c << " brick " << b;
        held += 64;
      } else {
        EXPECT_EQ(after[b], 0u) << "client " << c << " received frames of brick " << b;
        EXPECT_TRUE(untouched(*volumes[std::size_t(c)], b)) << "client " << c << " brick " << b;
      }
    }
    std::uint32_t active = 0;
    for (std::uint32_t i = 0; i < 128; ++i) active += volumes[std::size_t(c)]->state(i).updates > 0;
    EXPECT_EQ(active, held) << "client " << c;  // a client of both bricks holds all 128, as of one server
    EXPECT_EQ(clients[std::size_t(c)]->rejected_total(), 0u);
  }
  // Every client's views reached both servers.
  EXPECT_EQ(s0.server.clients(), 8u);
  EXPECT_EQ(s1.server.clients(), 8u);
  stop = true;
  relay_thread.join();
  // The relay's four clients want brick 0 alone: one subscription went upstream, and nothing of
  // server 1 came in (every byte the relay took is one of server 0's, topics included).
  EXPECT_EQ(relay_stats.subscriptions, 1u);
  EXPECT_GE(relay_stats.messages_in, std::uint64_t(ticks));
  EXPECT_LE(relay_stats.bytes_in, s0.server.bytes_published());
}

// Server 1 of 2 is lost and comes back while server 0 goes on: the client of both bricks says
// so for server 1 alone, keeps brick 1's probes, follows brick 0 throughout and takes a
// snapshot of the new server 1; the client of brick 0 alone notices nothing.
TEST(Bricks, OneServerLostAndBackTheOtherGoesOn) {
  BrickServer s0(address(3), {0, 2}, 21);
  auto s1 = std::make_unique<BrickServer>(address(4), BrickShare{1, 2}, 22);
  const std::string servers = address(3) + "," + address(4);
  std::vector<std::string> both_log, one_log;
  probes::ProbeVolume both_volume(grid(), 2), one_volume(grid(), 2);
  ProbeClient both(client_options(servers, "", 2, &both_log), both_volume, kScene);
  ProbeClient one(client_options(servers, "", 0, &one_log), one_volume, kScene);
  for (int k = 0; k < 300 && !(both.synced() && one.synced() && both.server_frame() >= 3); ++k) {
    s0.tick(5);
    s1->tick(5);
    both.poll(2);
    one.poll(2);
  }
  ASSERT_TRUE(both.synced() && one.synced());
  s1.reset();  // lost
  for (int k = 0; k < 150 && both.synced(); ++k) {
    s0.tick(5);
    both.poll(5);
    one.poll(2);
  }
  EXPECT_FALSE(both.synced());
  EXPECT_TRUE(one.synced());
  const std::uint64_t during = s0.frame;
  for (int k = 0; k < 5; ++k) {
    s0.tick(5);
    both.poll(5);
    one.poll(5);
  }
  EXPECT_TRUE(holds(both_volume, 0, s0.frame));   // brick 0 still followed
  EXPECT_GT(s0.frame, during);
  EXPECT_NE(both_volume.coefficients(4)[0], glm::vec3(0.0f));  // brick 1's probes kept
  s1 = std::make_unique<BrickServer>(address(4), BrickShare{1, 2}, 23);  // back, a new stream
  for (int k = 0; k < 300 && !(both.synced() && holds(both_volume, 1, s1->frame)); ++k) {
    s0.tick(5);
    s1->tick(5);
    both.poll(2);
    one.poll(2);
  }
  EXPECT_TRUE(both.synced());
  EXPECT_TRUE(holds(both_volume, 1, s1->frame));
  const auto count = [](const std::vector<std::string>& log, const std::string& text) {
    int n = 0;
    for (const std::string& l : log) n += l.find(text) != std::string::npos;
    return n;
  };
  EXPECT_EQ(count(both_log, "lost the probe server at " + address(4)), 1);
  EXPECT_EQ(count(both_log, "lost the probe server at " + address(3)), 0);
  EXPECT_EQ(count(both_log, "probe server back at " + address(4)), 1);
  EXPECT_EQ(count(one_log, "lost the probe server"), 0);
  EXPECT_EQ(both.reconnects(), 1u);
}

// What a publisher can get wrong about bricks is dropped and counted by kind, one log line each:
// a topic that names no brick (a longer one matches a subscription's prefix), a message of one
// part, a keyframe on the subscription, a frame with probes outside its topic's brick. Nothing
// of them reaches the volume.
TEST(Bricks, MalformedBrickMessagesAreDroppedAndCounted) {
  zmq::context_t context;
  zmq::socket_t publisher(context, zmq::socket_type::pub);
  publisher.set(zmq::sockopt::linger, 0);
  publisher.bind(address(5));
  probes::ProbeVolume all(grid(), 2);
  for (std::uint32_t i = 0; i < all.probe_count(); ++i) {
    all.set_sh(i, probe_at(i, 1));
    all.state(i).flags = 0;
    all.state(i).updates = 1;
  }
  PublishedProbes whole(all, kScene, 5, {.encoding = Encoding::kHalf});  // both bricks in one stream
  const std::vector<std::uint8_t> both = whole.publish(all, 1, 0, 0.0), keyframe = whole.snapshot();
  std::vector<std::string> log;
  probes::ProbeVolume mine(grid(), 2);
  ProbeClient client(client_options(address(5), "", 2, &log), mine, kScene);
  const std::string topic = brick_topic(0), longer = topic + "x";
  const auto enough = [&] {
    return client.rejected(RejectKind::kBadHeader) >= 4 && client.rejected(RejectKind::kBadIndex) >= 2 &&
           client.rejected(RejectKind::kSizeMismatch) >= 2;
  };
  for (int turn = 0; turn < 400 && !enough(); ++turn) {
    std::array<zmq::const_buffer, 2> long_topic = {zmq::buffer(longer), zmq::buffer(both)};
    std::array<zmq::const_buffer, 2> outside = {zmq::buffer(topic), zmq::buffer(both)};
    std::array<zmq::const_buffer, 2> snapshot = {zmq::buffer(topic), zmq::buffer(keyframe)};
    std::array<zmq::const_buffer, 1> one_part = {zmq::buffer(topic)};
    if (turn % 10 == 0)
      for (auto* m : {&long_topic, &outside, &snapshot}) zmq::send_multipart(publisher, *m);
    if (turn % 10 == 0) zmq::send_multipart(publisher, one_part);
    client.poll(5);
  }
  EXPECT_GE(client.rejected(RejectKind::kBadHeader), 4u);  // the long topic and the keyframe, twice each
  EXPECT_GE(client.rejected(RejectKind::kBadIndex), 2u);
  EXPECT_GE(client.rejected(RejectKind::kSizeMismatch), 2u);
  EXPECT_EQ(log.size(), 3u);  // one line per kind
  EXPECT_FALSE(client.ever_synced());
  EXPECT_TRUE(untouched(mine, 0));
  EXPECT_TRUE(untouched(mine, 1));
}

}  // namespace
}  // namespace ddish::net
