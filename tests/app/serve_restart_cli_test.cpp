// The probe service's fault test at the scale: one server and four clients on different
// displays (single view, stereo, a Looking Glass Portrait quilt, an 8 x 4 camera grid), the server
// killed (SIGKILL) and restarted 10 times. No client exits or stops writing frames while its
// server is gone; each notices every loss, takes a snapshot of every new server, and says so.
// Every wait is bounded, so a slow machine only makes the test slower, never hung.
//
// The reconnection times (the server's "serve: ... on tcp://" line, written once it has bound,
// to each client's "probe server back" line, both polled every 10 ms) are printed, and written as
// JSON where DDISH_RECONNECT_FIGURE names a file (scripts/net_figures.sh reports them); they are
// a measurement of this machine, so the test asserts the count of reconnections, not their time.
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "serve_process.h"

namespace {

struct Client {
  const char* name;
  std::vector<std::string> display;  // the display options of this client
};

// Tiny views: what is tested is the stream, not the pixels. The Portrait keeps its 3:4 tiles.
const std::vector<Client> kClients = {
    {"single", {"--width", "24", "--height", "24"}},
    {"stereo", {"--display", "stereo", "--width", "16", "--height", "18"}},
    {"portrait", {"--display", "looking-glass-portrait", "--width", "6", "--height", "8"}},
    {"grid", {"--display", "lightfield-32x720p", "--width", "8", "--height", "5"}},
};
constexpr int kRestarts = 10;

using Clock = std::chrono::steady_clock;

double seconds_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

std::size_t frames_written(const cli::fs::path& dir) {
  if (!cli::fs::exists(dir)) return 0;
  std::size_t n = 0;
  for (const auto& e : cli::fs::directory_iterator(dir)) n += e.path().extension() == ".png";
  return n;
}

class ServeRestart : public cli::TempDirTest {
 protected:
  ServeRestart() : TempDirTest("ddish_restart_") {}
};

TEST_F(ServeRestart, FourClientsSurviveTenServerRestarts) {
  const std::string bind = cli::address(8);
  const std::string scene = std::string(DDISH_SOURCE_DIR) + "/scenes/cornell_box.gltf";
  const auto server_args = [&] {
    return std::vector<std::string>{"serve", scene, "--bind", bind, "--grid", "4,4,4", "--probe-samples", "16",
                                    "--bounces", "2", "--schedule", "uniform", "--fps", "30", "--seconds", "60"};
  };
  std::vector<std::unique_ptr<cli::Process>> views;
  for (const Client& c : kClients) {
    std::vector<std::string> args = {"view", scene, "--grid", "4,4,4", "--msaa", "1", "--frames", "100000",
                                     "--every", "--frame-wait-ms", "30", "--stale-ms", "300", "--wait-ms", "0",
                                     "--connect", bind, "--out", (dir_ / c.name).string(), "--timings",
                                     (dir_ / (std::string(c.name) + ".json")).string()};
    args.insert(args.end(), c.display.begin(), c.display.end());
    views.push_back(std::make_unique<cli::Process>(args, dir_ / (std::string(c.name) + ".log")));
  }
  const auto log_of = [&](std::size_t c) { return dir_ / (std::string(kClients[c].name) + ".log"); };
  // Polls (bounded) until every client has written `text` at least `count` times; the time at
  // which each one did.
  const auto wait_all = [&](const std::string& text, std::size_t count, double seconds) {
    std::vector<Clock::time_point> when(kClients.size(), Clock::time_point{});
    const auto end = Clock::now() + std::chrono::duration<double>(seconds);
    std::size_t left = kClients.size();
    while (left > 0 && Clock::now() < end) {
      for (std::size_t c = 0; c < kClients.size(); ++c)
        if (when[c] == Clock::time_point{} && cli::count_in(log_of(c), text) >= count) {
          when[c] = Clock::now();
          --left;
        }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return left == 0 ? when : std::vector<Clock::time_point>{};
  };

  std::vector<std::vector<double>> reconnect_s(kClients.size());
  std::unique_ptr<cli::Process> server;  // the last one stays up until the clients are stopped
  for (int k = 0; k <= kRestarts; ++k) {
    const cli::fs::path server_log = dir_ / ("serve" + std::to_string(k));
    server = std::make_unique<cli::Process>(server_args(), server_log);
    ASSERT_TRUE(cli::wait_for(server_log, " on tcp://", 30.0)) << cli::slurp(server_log);
    const Clock::time_point ready = Clock::now();
    // The first server gives each client its first snapshot; each later one is a return.
    const std::vector<Clock::time_point> back =
        k == 0 ? wait_all("snapshot of frame", 1, 60.0) : wait_all("probe server back", std::size_t(k), 60.0);
    ASSERT_EQ(back.size(), kClients.size()) << "server " << k << ": not every client took a snapshot";
    if (k > 0)
      for (std::size_t c = 0; c < kClients.size(); ++c) reconnect_s[c].push_back(seconds_between(ready, back[c]));
    if (k == kRestarts) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    server->kill(SIGKILL);
    ASSERT_EQ(wait_all("lost the probe server", std::size_t(k + 1), 60.0).size(), kClients.size())
        << "loss " << k + 1 << " not noticed by every client";
    // Every client goes on writing frames with the probes it holds while no server is there.
    std::vector<std::size_t> before;
    for (const Client& c : kClients) before.push_back(frames_written(dir_ / c.name));
    for (std::size_t c = 0; c < kClients.size(); ++c)
      for (int i = 0; i < 3000 && frames_written(dir_ / kClients[c].name) < before[c] + 2; ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    for (std::size_t c = 0; c < kClients.size(); ++c)
      EXPECT_GE(frames_written(dir_ / kClients[c].name), before[c] + 2)
          << kClients[c].name << " stopped writing frames during outage " << k + 1;
  }

  nlohmann::json figure;
  for (std::size_t c = 0; c < kClients.size(); ++c) {
    // SIGTERM: the client finishes the frame it is on, writes it and its timings, exits 128 + 15.
    EXPECT_EQ(views[c]->stop(SIGTERM, 60.0), 128 + SIGTERM) << cli::slurp(log_of(c));
    const std::string log = cli::slurp(log_of(c));
    EXPECT_EQ(cli::count_in(log_of(c), "lost the probe server"), std::size_t(kRestarts)) << log;
    EXPECT_EQ(cli::count_in(log_of(c), "probe server back"), std::size_t(kRestarts)) << log;
    const nlohmann::json t = nlohmann::json::parse(cli::slurp(dir_ / (std::string(kClients[c].name) + ".json")));
    EXPECT_EQ(t["frames"].size(), frames_written(dir_ / kClients[c].name)) << "a frame without its image";
    std::vector<double> r = reconnect_s[c];
    std::sort(r.begin(), r.end());
    std::printf("%-8s %zu frames, reconnection after the server's return: median %.3f s, max %.3f s\n",
                kClients[c].name, std::size_t(t["frames"].size()), r[r.size() / 2], r.back());
    figure[kClients[c].name] = {{"frames", t["frames"].size()}, {"reconnect_s", reconnect_s[c]}};
  }
  if (const char* out = std::getenv("DDISH_RECONNECT_FIGURE")) std::ofstream(out) << figure.dump(1) << "\n";
}

}  // namespace
