// What travels on the wire: a TCP relay between a client and its server records every byte both
// ways. In plaintext the probe frames' magic "DDPF" is in the capture; with CurveZMQ the client
// is served just the same, and the capture holds no magic (neither "DDPF" nor the view
// messages' "DDVW"): the traffic is encrypted.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <mutex>
#include <optional>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "net/curve_keys.h"
#include "net/probe_client.h"
#include "net/probe_server.h"
#include "net/published_probes.h"
#include "net_test_util.h"

namespace ddish::net {
namespace {

// Below Linux's ephemeral range (32768-60999), where another test's outgoing connection could
// hold the port for a moment (this test failed so under ctest -j2), and below the other net
// tests' ranges (16000 up).
int base_port(int test) { return 10000 + int(getpid() % 700) * 8 + 4 * test; }

int listen_on(int port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  const int one = 1;
  ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(std::uint16_t(port));
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 || ::listen(fd, 4) != 0) {
    ::close(fd);
    return -1;
  }
  return fd;
}

int connect_to(int port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(std::uint16_t(port));
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
    ::close(fd);
    return -1;
  }
  return fd;
}

// Forwards listen port -> upstream port (one connection at a time), recording the bytes.
class Relay {
 public:
  Relay(int listen_port, int upstream_port) : listener_(listen_on(listen_port)), upstream_(upstream_port) {
    thread_ = std::thread([this] { run(); });
  }
  ~Relay() {
    stop_ = true;
    thread_.join();
    if (listener_ >= 0) ::close(listener_);
  }
  bool listening() const { return listener_ >= 0; }
  std::string captured() {
    std::lock_guard<std::mutex> lock(mutex_);
    return captured_;
  }

 private:
  void run() {
    while (!stop_ && listener_ >= 0) {
      pollfd p{listener_, POLLIN, 0};
      if (::poll(&p, 1, 20) <= 0) continue;
      const int down = ::accept(listener_, nullptr, nullptr);
      const int up = connect_to(upstream_);
      if (down < 0 || up < 0) {
        if (down >= 0) ::close(down);
        if (up >= 0) ::close(up);
        continue;
      }
      pump(down, up);
      ::close(down);
      ::close(up);
    }
  }
  void pump(int a, int b) {
    char buf[65536];
    while (!stop_) {
      pollfd p[2] = {{a, POLLIN, 0}, {b, POLLIN, 0}};
      if (::poll(p, 2, 20) <= 0) continue;
      for (int k = 0; k < 2; ++k) {
        if (!(p[k].revents & (POLLIN | POLLHUP | POLLERR))) continue;
        const ssize_t n = ::read(p[k].fd, buf, sizeof buf);
        if (n <= 0) return;
        {
          std::lock_guard<std::mutex> lock(mutex_);
          captured_.append(buf, std::size_t(n));
        }
        if (::write(p[1 - k].fd, buf, std::size_t(n)) != n) return;
      }
    }
  }
  int listener_;
  int upstream_;
  std::atomic<bool> stop_{false};
  std::mutex mutex_;
  std::string captured_;
  std::thread thread_;
};

probes::ProbeGrid grid() { return probes::ProbeGrid(scene::Aabb{glm::vec3(0.0f), glm::vec3(2.0f)}, {3, 3, 3}); }

// Serves through two relays (publisher and request ports) and returns the capture.
std::string capture(int test, bool curve, bool& served) {
  const int server_port = base_port(test), relay_port = server_port + 2;
  const CurveKeyPair server_keys = generate_curve_keys(), client_keys = generate_curve_keys();
  std::optional<CurveServerKeys> server_curve;
  if (curve) server_curve = CurveServerKeys{server_keys.secret_z85, {client_keys.public_z85}};
  probes::ProbeVolume volume(grid(), 2);
  std::mt19937_64 rng(3);
  for (std::uint32_t i = 0; i < volume.probe_count(); ++i) {
    volume.set_sh(i, test::radiance_probe(rng, 2, 1.0f));
    volume.state(i).flags = 0;
    volume.state(i).updates = 1;
  }
  PublishedProbes published(volume, 5, 1, {.encoding = Encoding::kHalf});
  ProbeServer server({.bind = "tcp://127.0.0.1:" + std::to_string(server_port), .curve = server_curve});
  Relay pub(relay_port, server_port), req(relay_port + 1, server_port + 1);
  EXPECT_TRUE(pub.listening() && req.listening());
  ClientOptions co;
  co.connect = "tcp://127.0.0.1:" + std::to_string(relay_port);
  co.snapshot_retry_ms = 50;
  if (curve) co.curve = CurveClientKeys{server_keys.public_z85, client_keys.public_z85, client_keys.secret_z85};
  probes::ProbeVolume mine(grid(), 2);
  ProbeClient client(co, mine, 5);
  std::uint64_t frame = 0;
  for (int turn = 0; turn < 200 && !(client.synced() && client.server_frame() >= 5); ++turn) {
    for (glm::vec3& c : volume.coefficients(std::uint32_t(turn) % volume.probe_count())) c *= 1.1f;
    server.publish(0, published.publish(volume, ++frame, 0, 0.0));
    server.serve_requests(5, [&](std::uint32_t) { return published.snapshot(); });
    client.send_views({scene::look_at_view({0, 1, 3}, {0, 1, 0}, {0, 1, 0}, 1.0f, 32, 32)});
    client.poll(5);
  }
  served = client.synced() && client.server_frame() >= 5;
  return pub.captured() + req.captured();
}

TEST(CurveCapture, PlaintextShowsTheMagicCurveDoesNot) {
  bool served = false;
  const std::string plain = capture(0, false, served);
  ASSERT_TRUE(served);
  EXPECT_NE(plain.find("DDPF"), std::string::npos);
  EXPECT_NE(plain.find("DDVW"), std::string::npos);
  const std::string encrypted = capture(1, true, served);
  ASSERT_TRUE(served);
  EXPECT_GT(encrypted.size(), 2000u);  // the frames did pass through the relay
  EXPECT_EQ(encrypted.find("DDPF"), std::string::npos);
  EXPECT_EQ(encrypted.find("DDVW"), std::string::npos);
}

}  // namespace
}  // namespace ddish::net
