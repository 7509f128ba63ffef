// ddish relay --connect tcp://HOST:PORT[,tcp://HOST:PORT...] [--bind tcp://127.0.0.1:PORT]
//             [--insecure] [--seconds S]
//
// The probe stream's fan-out (net/relay.h): a zmq_proxy XSUB/XPUB forwarder that subscribes to
// the publishers of one or more `ddish serve`s and republishes their brick frames at --bind, so
// that many `ddish view --relay ADDR --connect SERVERS` clients take one connection here instead
// of one per server, and each server sends a brick once per relay however many clients want it.
// Clients' subscriptions (brick topics) pass upstream; snapshots and views go from each client
// to each server directly. It binds loopback unless --insecure (the relay speaks plaintext).
// --seconds S stops it after S seconds, SIGINT / SIGTERM at once; either way it prints what it
// forwarded.
#include <chrono>
#include <csignal>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>

#include "app/commands.h"
#include "net/endpoint.h"
#include "net/relay.h"

namespace ddish::app {
namespace {

volatile std::sig_atomic_t g_stop = 0;
void request_stop(int) { g_stop = 1; }

struct RelayArgs {
  std::string connect;
  std::string bind = "tcp://127.0.0.1:5600";
  bool insecure = false;
  double seconds = 0.0;
};

int run_relay(const RelayArgs& a) {
  if (!(a.seconds >= 0.0)) throw std::invalid_argument("--seconds must be >= 0");
  const std::vector<net::Endpoint> servers = net::parse_endpoint_list(a.connect);
  const net::Endpoint bind = net::parse_endpoint(a.bind);
  if (!bind.loopback() && !a.insecure)
    throw std::invalid_argument("--bind " + a.bind + " is not a loopback address: the relay speaks plaintext, so serving it needs --insecure");
  net::RelayOptions options;
  for (const net::Endpoint& e : servers) options.upstream.push_back(e.publisher());
  options.bind = a.bind;
  net::Relay relay(options);
  std::fprintf(stderr, "relay: on %s, forwarding %zu servers (%s)\n", bind.publisher().c_str(), servers.size(),
               a.connect.c_str());
  std::fflush(stderr);
  std::signal(SIGINT, request_stop);
  std::signal(SIGTERM, request_stop);
  const auto start = std::chrono::steady_clock::now();
  const net::RelayStats stats = relay.run([&] {
    return g_stop != 0 ||
           (a.seconds > 0.0 && std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >= a.seconds);
  });
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::fprintf(stderr,
               "relay: stopped after %.1f s: %llu messages (%llu bytes) in, %llu messages (%llu bytes) out, "
               "%llu subscription messages upstream\n",
               seconds, static_cast<unsigned long long>(stats.messages_in), static_cast<unsigned long long>(stats.bytes_in),
               static_cast<unsigned long long>(stats.messages_out), static_cast<unsigned long long>(stats.bytes_out),
               static_cast<unsigned long long>(stats.subscriptions));
  return 0;
}

Action make_relay(CLI::App& root) {
  auto a = std::make_shared<RelayArgs>();
  CLI::App* cmd = root.add_subcommand("relay", "fan-out of ddish serve probe streams to many ddish view clients (XSUB/XPUB)");
  cmd->add_option("--connect", a->connect, "the servers' addresses, tcp://HOST:PORT, comma-separated")->required();
  cmd->add_option("--bind", a->bind, "address the clients subscribe at (view --relay)")->capture_default_str();
  cmd->add_flag("--insecure", a->insecure, "allow a non-loopback --bind");
  cmd->add_option("--seconds", a->seconds, "stop after this many seconds (0: run until interrupted)")
      ->capture_default_str();
  return [a]() { return run_relay(*a); };
}

}  // namespace

DDISH_COMMAND(63, make_relay);

}  // namespace ddish::app
