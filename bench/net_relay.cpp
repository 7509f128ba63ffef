// net_relay: what a `ddish relay` forwards (docs/scaling.md). One probe server publishes real
// brick frames (compact L2, 4x4x4 probes per brick, every probe changed every tick: the worst
// case of the change-driven stream) as fast as it can for --seconds; a relay (net/relay.h, the
// zmq_proxy XSUB/XPUB forwarder) forwards them to --clients probe clients, which decode and
// apply every frame as `ddish view` does. All in one process on loopback: the server and the
// relay each in a thread, the clients taking turns in another. Prints one CSV row per client
// count. On a machine shared with the clients and the server this is a lower bound on the
// relay's own rate.
// The server ticks at --fps (one frame per brick per tick). Unthrottled, with clients that cannot
// keep up, libzmq 4.3.4 was seen to abort ("Assertion failed: _input_stopped", libzmq issue
// 3937), so the rate is bounded.
// Usage: net_relay [--grid N] [--fps F] [--seconds S] [--clients 1,4,8] [--port P]
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "net/bricks.h"
#include "net/probe_client.h"
#include "net/probe_server.h"
#include "net/published_probes.h"
#include "net/relay.h"
#include "sh/projection.h"

using namespace ddish;

int main(int argc, char** argv) {
  int n = 16, port = 23000;
  double seconds = 3.0, fps = 30.0;
  std::vector<int> client_counts = {1, 4, 8};
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string k = argv[i], v = argv[i + 1];
    if (k == "--grid") n = std::stoi(v);
    else if (k == "--seconds") seconds = std::stod(v);
    else if (k == "--port") port = std::stoi(v);
    else if (k == "--fps") fps = std::stod(v);
    else if (k == "--clients") {
      client_counts.clear();
      std::stringstream ss(v);
      for (std::string t; std::getline(ss, t, ',');) client_counts.push_back(std::stoi(t));
    } else {
      std::fprintf(stderr, "net_relay: unknown option %s\n", k.c_str());
      return 2;
    }
  }
  const probes::ProbeGrid grid(scene::Aabb{glm::vec3(0.0f), glm::vec3(float(n))}, {n, n, n});
  const net::BrickLayout layout(grid);
  std::printf("clients,grid_probes,bricks,fps,seconds,ticks,relay_messages_in_per_s,relay_mb_in_per_s,"
              "relay_messages_out_per_s,relay_mb_out_per_s,client_frames_per_s_each,client_mb_per_s_each,"
              "client_frames_applied_fraction\n");
  for (int clients : client_counts) {
    const std::string server_address = "tcp://127.0.0.1:" + std::to_string(port);
    const std::string relay_address = "tcp://127.0.0.1:" + std::to_string(port + 2);
    port += 4;
    probes::ProbeVolume volume(grid, 2);
    std::vector<net::PublishedProbes> streams;
    for (std::uint32_t b = 0; b < layout.brick_count(); ++b)
      streams.emplace_back(volume, 7, 1, net::StreamOptions{.encoding = net::Encoding::kCompact}, layout.probes(b));
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<float> u(0.2f, 1.0f);
    for (std::uint32_t i = 0; i < volume.probe_count(); ++i) {
      volume.set_sh(i, sh::project_direction(glm::normalize(glm::vec3(u(rng) - 0.6f, u(rng) - 0.6f, 1.0f)),
                                             glm::vec3(u(rng), u(rng), u(rng)), 2));
      volume.coefficients(i)[0] += glm::vec3(2.0f);
      volume.state(i).flags = 0;
      volume.state(i).updates = 1;
    }
    net::ProbeServer server({.bind = server_address, .send_hwm = int(8 * layout.brick_count())});
    net::Relay relay({.upstream = {server_address}, .bind = relay_address});
    std::atomic<bool> stop{false}, go{false};
    net::RelayStats stats;
    std::thread relay_thread([&] { stats = relay.run([&] { return stop.load(); }); });
    std::vector<std::unique_ptr<probes::ProbeVolume>> volumes;
    std::vector<std::unique_ptr<net::ProbeClient>> probe_clients;
    for (int c = 0; c < clients; ++c) {
      volumes.push_back(std::make_unique<probes::ProbeVolume>(grid, 2));
      net::ClientOptions o;
      o.connect = server_address;
      o.relay = relay_address;
      probe_clients.push_back(std::make_unique<net::ProbeClient>(o, *volumes.back(), 7));
    }
    std::uint64_t ticks = 0;
    std::thread server_thread([&] {
      const auto snapshot = [&](std::uint32_t b) {
        return b < streams.size() ? streams[b].snapshot() : std::vector<std::uint8_t>{};
      };
      auto next = std::chrono::steady_clock::now();
      while (!stop) {
        next += std::chrono::microseconds(std::int64_t(1e6 / fps));
        std::this_thread::sleep_until(next);
        ++ticks;
        for (std::uint32_t i = 0; i < volume.probe_count(); ++i)  // every probe moves a little
          volume.coefficients(i)[0] *= (ticks % 2) ? 1.01f : 1.0f / 1.01f;
        if (go)
          for (std::uint32_t b = 0; b < streams.size(); ++b)
            server.publish(b, streams[b].publish(volume, ticks, net::steady_now_us(), 0.0));
        else
          for (std::uint32_t b = 0; b < streams.size(); ++b) streams[b].publish(volume, ticks, 0, 0.0);
        server.serve_requests(0, snapshot);
      }
    });
    // Everyone connected and synced first (bounded), then the measured interval.
    for (int k = 0; k < 400; ++k) {
      bool all = true;
      for (auto& c : probe_clients) {
        c->poll(5);
        all = all && c->synced();
      }
      if (all) break;
    }
    std::vector<std::uint64_t> received_before(std::size_t(clients), 0);
    for (int c = 0; c < clients; ++c)
      for (std::uint64_t f : probe_clients[std::size_t(c)]->frames_per_brick()) received_before[std::size_t(c)] += f;
    go = true;
    const auto start = std::chrono::steady_clock::now();
    std::uint64_t applied = 0, bytes = 0;
    while (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < seconds)
      for (auto& c : probe_clients) {
        const net::ClientPoll p = c->poll(0);
        applied += p.frames_applied;
        bytes += p.bytes;
      }
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    stop = true;
    server_thread.join();
    relay_thread.join();
    std::uint64_t received = 0;
    for (int c = 0; c < clients; ++c) {
      std::uint64_t now = 0;
      for (std::uint64_t f : probe_clients[std::size_t(c)]->frames_per_brick()) now += f;
      received += now - received_before[std::size_t(c)];
    }
    // The relay's counts cover its whole run (the warm-up's few frames are not published).
    std::printf("%d,%u,%u,%.0f,%.2f,%llu,%.0f,%.2f,%.0f,%.2f,%.0f,%.2f,%.3f\n", clients, grid.probe_count(),
                layout.brick_count(), fps, elapsed, static_cast<unsigned long long>(ticks), double(stats.messages_in) / elapsed,
                double(stats.bytes_in) / elapsed / 1e6, double(stats.messages_out) / elapsed,
                double(stats.bytes_out) / elapsed / 1e6, double(received) / clients / elapsed,
                double(bytes) / clients / elapsed / 1e6, received > 0 ? double(applied) / double(received) : 0.0);
    std::fflush(stdout);
  }
  return 0;
}
