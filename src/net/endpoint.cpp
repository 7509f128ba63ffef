#include "net/endpoint.h"

#include <charconv>
#include <stdexcept>

namespace ddish::net {

std::string Endpoint::publisher() const { return "tcp://" + host + ":" + std::to_string(port); }
std::string Endpoint::requests() const { return "tcp://" + host + ":" + std::to_string(port + 1); }

bool Endpoint::loopback() const {
  return host == "localhost" || host == "[::1]" || host.rfind("127.", 0) == 0;
}

Endpoint parse_endpoint(const std::string& address) {
  const std::string scheme = "tcp://";
  if (address.rfind(scheme, 0) != 0)
    throw std::invalid_argument("address '" + address + "' is not tcp://HOST:PORT");
  const std::string rest = address.substr(scheme.size());
  const std::size_t colon = rest.rfind(':');
  if (colon == std::string::npos || colon == 0 || colon + 1 == rest.size())
    throw std::invalid_argument("address '" + address + "' is not tcp://HOST:PORT");
  Endpoint e;
  e.host = rest.substr(0, colon);
  const std::string port = rest.substr(colon + 1);
  const auto [end, ec] = std::from_chars(port.data(), port.data() + port.size(), e.port);
  if (ec != std::errc() || end != port.data() + port.size() || e.port < 1 || e.port > 65534)
    throw std::invalid_argument("address '" + address + "': port must be 1..65534 (PORT+1 is used too)");
  if (e.host.find_first_of("/ *") != std::string::npos)
    throw std::invalid_argument("address '" + address + "': a host name or address, not a pattern");
  return e;
}

std::vector<Endpoint> parse_endpoint_list(const std::string& addresses) {
  std::vector<Endpoint> out;
  std::size_t from = 0;
  while (true) {
    const std::size_t comma = addresses.find(',', from);
    const Endpoint e = parse_endpoint(addresses.substr(from, comma == std::string::npos ? std::string::npos : comma - from));
    for (const Endpoint& seen : out)
      if (seen.publisher() == e.publisher())
        throw std::invalid_argument("address '" + e.publisher() + "' is given twice");
    out.push_back(e);
    if (comma == std::string::npos) break;
    from = comma + 1;
  }
  return out;
}

}  // namespace ddish::net
