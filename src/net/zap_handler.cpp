#include "net/zap_handler.h"

#include <array>
#include <vector>

#include <zmq_addon.hpp>

namespace ddish::net {

ZapHandler::ZapHandler(zmq::context_t& context, std::set<std::string> allowed_z85,
                       std::function<void(const std::string&)> log)
    : socket_(context, zmq::socket_type::rep), allowed_(std::move(allowed_z85)), log_(std::move(log)) {
  socket_.set(zmq::sockopt::linger, 0);
  socket_.bind("inproc://zeromq.zap.01");
  thread_ = std::thread([this] { run(); });
}

ZapHandler::~ZapHandler() {
  stop_ = true;
  thread_.join();
}

void ZapHandler::run() {
  while (!stop_) {
    zmq::pollitem_t item{socket_.handle(), 0, ZMQ_POLLIN, 0};
    zmq::poll(&item, 1, std::chrono::milliseconds(50));
    if (!(item.revents & ZMQ_POLLIN)) continue;
    std::vector<zmq::message_t> request;
    if (!zmq::recv_multipart(socket_, std::back_inserter(request), zmq::recv_flags::dontwait)) continue;
    // version, request id, domain, address, identity, mechanism, credentials...
    const std::string version = request.size() > 0 ? request[0].to_string() : "";
    const std::string id = request.size() > 1 ? request[1].to_string() : "";
    bool ok = false;
    if (request.size() >= 7 && version == "1.0" && request[5].to_string() == "CURVE" && request[6].size() == 32) {
      char z85[41];
      zmq_z85_encode(z85, static_cast<const std::uint8_t*>(request[6].data()), 32);
      ok = allowed_.count(z85) > 0;
      if (!ok && refused_.load() == 0 && log_)
        log_(std::string("refused a client whose key is not allowed: ") + z85 + "; further ones are counted");
    }
    ++(ok ? admitted_ : refused_);
    std::array<zmq::const_buffer, 6> reply = {zmq::str_buffer("1.0"), zmq::buffer(id),
                                              ok ? zmq::str_buffer("200") : zmq::str_buffer("400"),
                                              ok ? zmq::str_buffer("OK") : zmq::str_buffer("key not allowed"),
                                              zmq::str_buffer(""), zmq::str_buffer("")};
    zmq::send_multipart(socket_, reply);
  }
}

}  // namespace ddish::net
