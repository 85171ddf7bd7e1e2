// A thin RAII wrapper over the ZeroMQ C API: the only ZeroMQ code of the project besides the coupler loop.
// Every message is a list of frames; errors are CouplingError with zmq_strerror and the endpoint.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace cosim::coupling {

using Frames = std::vector<std::string>;

class ZmqContext {
 public:
  ZmqContext();
  ~ZmqContext();
  ZmqContext(const ZmqContext&) = delete;
  ZmqContext& operator=(const ZmqContext&) = delete;
  void* get() const { return ctx_; }

 private:
  void* ctx_;
};

class ZmqSocket {
 public:
  enum class Type { Dealer, Router, Pair };
  ZmqSocket(ZmqContext& ctx, Type type);
  ~ZmqSocket();
  ZmqSocket(const ZmqSocket&) = delete;
  ZmqSocket& operator=(const ZmqSocket&) = delete;

  void bind(const std::string& endpoint);
  void connect(const std::string& endpoint);
  // Milliseconds pending messages are kept after close (0: dropped at once).
  void set_linger(int ms);
  // ROUTER: sending to an unknown routing id fails (EHOSTUNREACH) instead of being dropped.
  void set_router_mandatory();
  // Messages larger than `bytes` are not received: libzmq drops the connection that sends one, before it is
  // read into memory.
  void set_max_message_size(std::int64_t bytes);
  // The endpoint actually bound (resolves tcp://127.0.0.1:* to the chosen port).
  std::string last_endpoint() const;

  // Returns false when the message could not be routed (ROUTER mandatory, peer gone) or the send would
  // block for longer than timeout_ms; throws on other errors.
  bool send(const Frames& frames, int timeout_ms = 1000);
  // Waits up to timeout_ms (-1: forever) for one message; false when none arrived.
  bool receive(Frames& frames, int timeout_ms);

  // Publishes this socket's disconnections as events on `inproc_endpoint` (a Pair socket connected there
  // receives them); is_disconnection tells such an event.
  void monitor_disconnections(const std::string& inproc_endpoint);
  static bool is_disconnection(const Frames& event);

  void* handle() const { return sock_; }

 private:
  void* sock_;
  std::string endpoint_;
};

}  // namespace cosim::coupling
