// The server's ZAP handler (ZeroMQ RFC 27): a thread answering the library's authentication
// requests on inproc://zeromq.zap.01 of the server's context. It admits a CURVE client only when
// its public key is in the allowed set; every refusal is counted and the first one logged.
#pragma once

#include <atomic>
#include <functional>
#include <set>
#include <string>
#include <thread>

#include <zmq.hpp>

namespace ddish::net {

class ZapHandler {
 public:
  // Binds the ZAP endpoint in `context` (before any CURVE socket binds) and starts the thread.
  ZapHandler(zmq::context_t& context, std::set<std::string> allowed_z85,
             std::function<void(const std::string&)> log);
  ~ZapHandler();  // stops the thread
  ZapHandler(const ZapHandler&) = delete;
  ZapHandler& operator=(const ZapHandler&) = delete;

  std::uint64_t refused() const { return refused_.load(); }
  std::uint64_t admitted() const { return admitted_.load(); }

 private:
  void run();
  zmq::socket_t socket_;
  std::set<std::string> allowed_;
  std::function<void(const std::string&)> log_;
  std::atomic<bool> stop_{false};
  std::atomic<std::uint64_t> refused_{0}, admitted_{0};
  std::thread thread_;
};

}  // namespace ddish::net
