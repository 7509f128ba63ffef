// The addresses of a probe server. One address names both sockets: tcp://HOST:PORT is the
// publisher (probe frames), tcp://HOST:PORT+1 the request socket (snapshots, clients' views).
#pragma once

#include <string>
#include <vector>

namespace ddish::net {

struct Endpoint {
  std::string host;
  int port = 0;
  std::string publisher() const;  // tcp://host:port
  std::string requests() const;   // tcp://host:port+1
  bool loopback() const;          // 127.0.0.0/8, ::1 or localhost
};

// Parses tcp://HOST:PORT (PORT 1..65534, HOST a name, an IPv4 address or [IPv6]); throws
// std::invalid_argument with the reason otherwise.
Endpoint parse_endpoint(const std::string& address);

// Several servers, one address each, separated by commas (`view --connect A,B`); throws as
// parse_endpoint does, or for an empty list or an address given twice.
std::vector<Endpoint> parse_endpoint_list(const std::string& addresses);

}  // namespace ddish::net
