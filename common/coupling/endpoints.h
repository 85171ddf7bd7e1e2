// The coupler's two endpoints: the data endpoint the launcher chose and, derived from it, the endpoint of its
// heartbeat thread (docs/protocol.md, "Sockets").
#pragma once

#include <stdexcept>
#include <string>
#include <utility>

namespace cosim::coupling {

namespace detail {

// "tcp://HOST:PORT" -> {HOST, PORT}; HOST may be bracketed ([::1]).
inline std::pair<std::string, std::string> tcp_host_port(const std::string& endpoint) {
  const std::string rest = endpoint.substr(6);
  const std::size_t colon = rest.rfind(':');
  if (colon == std::string::npos) throw std::invalid_argument("tcp endpoint without a port: " + endpoint);
  return {rest.substr(0, colon), rest.substr(colon + 1)};
}

}  // namespace detail

// Where the coupler binds its heartbeat socket, from its data endpoint:
//   ipc://DIR/coupler.sock -> ipc://DIR/coupler-hb.sock (any other ipc name: NAME-hb), inproc likewise;
//   tcp://HOST:PORT        -> tcp://HOST:* (a port of the system's choosing, told in Welcome.heartbeat_endpoint).
inline std::string heartbeat_bind_endpoint(const std::string& data_endpoint) {
  if (data_endpoint.starts_with("tcp://")) return "tcp://" + detail::tcp_host_port(data_endpoint).first + ":*";
  const std::string suffix = ".sock";
  if (data_endpoint.size() > suffix.size() &&
      data_endpoint.compare(data_endpoint.size() - suffix.size(), suffix.size(), suffix) == 0)
    return data_endpoint.substr(0, data_endpoint.size() - suffix.size()) + "-hb" + suffix;
  return data_endpoint + "-hb";
}

// The heartbeat endpoint a solver connects to: Welcome.heartbeat_endpoint as the coupler bound it, with a
// wildcard host (tcp://0.0.0.0:P, tcp://*:P, tcp://[::]:P) replaced by the host of the data endpoint the solver
// reached the coupler at; empty (a coupler without a heartbeat thread): the data endpoint.
inline std::string heartbeat_connect_endpoint(const std::string& welcome_endpoint, const std::string& data_endpoint) {
  if (welcome_endpoint.empty()) return data_endpoint;
  if (!welcome_endpoint.starts_with("tcp://") || !data_endpoint.starts_with("tcp://")) return welcome_endpoint;
  const auto [host, port] = detail::tcp_host_port(welcome_endpoint);
  if (host == "0.0.0.0" || host == "*" || host == "[::]")
    return "tcp://" + detail::tcp_host_port(data_endpoint).first + ":" + port;
  return welcome_endpoint;
}

}  // namespace cosim::coupling
