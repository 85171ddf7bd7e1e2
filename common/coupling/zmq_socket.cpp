#include "common/coupling/zmq_socket.h"

#include <zmq.h>

#include <cerrno>
#include <cstdint>
#include <cstring>

#include "common/coupling/errors.h"

namespace cosim::coupling {

namespace {
[[noreturn]] void fail(const std::string& what, const std::string& endpoint) {
  throw CouplingError("ZeroMQ " + what + (endpoint.empty() ? "" : " (" + endpoint + ")") + ": " +
                      zmq_strerror(zmq_errno()));
}
}  // namespace

ZmqContext::ZmqContext() : ctx_(zmq_ctx_new()) {
  if (!ctx_) fail("context", "");
}
ZmqContext::~ZmqContext() { zmq_ctx_term(ctx_); }

ZmqSocket::ZmqSocket(ZmqContext& ctx, Type type)
    : sock_(zmq_socket(ctx.get(), type == Type::Dealer   ? ZMQ_DEALER
                                  : type == Type::Router ? ZMQ_ROUTER
                                                         : ZMQ_PAIR)) {
  if (!sock_) fail("socket", "");
  set_linger(0);
}

ZmqSocket::~ZmqSocket() { zmq_close(sock_); }

void ZmqSocket::bind(const std::string& endpoint) {
  endpoint_ = endpoint;
  if (zmq_bind(sock_, endpoint.c_str()) != 0) fail("cannot bind", endpoint);
}

void ZmqSocket::connect(const std::string& endpoint) {
  endpoint_ = endpoint;
  if (zmq_connect(sock_, endpoint.c_str()) != 0) fail("cannot connect", endpoint);
}

void ZmqSocket::set_linger(int ms) {
  if (zmq_setsockopt(sock_, ZMQ_LINGER, &ms, sizeof ms) != 0) fail("linger", endpoint_);
}

void ZmqSocket::set_router_mandatory() {
  int on = 1;
  if (zmq_setsockopt(sock_, ZMQ_ROUTER_MANDATORY, &on, sizeof on) != 0) fail("router_mandatory", endpoint_);
}

void ZmqSocket::set_max_message_size(std::int64_t bytes) {
  if (zmq_setsockopt(sock_, ZMQ_MAXMSGSIZE, &bytes, sizeof bytes) != 0) fail("maxmsgsize", endpoint_);
}

void ZmqSocket::monitor_disconnections(const std::string& inproc_endpoint) {
  if (zmq_socket_monitor(sock_, inproc_endpoint.c_str(), ZMQ_EVENT_DISCONNECTED) != 0)
    fail("socket monitor", inproc_endpoint);
}

// A monitor event: frame 1 holds the event (uint16) and a value (uint32), frame 2 the endpoint.
bool ZmqSocket::is_disconnection(const Frames& event) {
  std::uint16_t id = 0;
  if (event.size() != 2 || event[0].size() < sizeof id) return false;
  std::memcpy(&id, event[0].data(), sizeof id);
  return id == ZMQ_EVENT_DISCONNECTED;
}

std::string ZmqSocket::last_endpoint() const {
  char buf[512];
  size_t len = sizeof buf;
  if (zmq_getsockopt(sock_, ZMQ_LAST_ENDPOINT, buf, &len) != 0) fail("last_endpoint", endpoint_);
  return std::string(buf);
}

bool ZmqSocket::send(const Frames& frames, int timeout_ms) {
  if (zmq_setsockopt(sock_, ZMQ_SNDTIMEO, &timeout_ms, sizeof timeout_ms) != 0) fail("sndtimeo", endpoint_);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const int flags = i + 1 < frames.size() ? ZMQ_SNDMORE : 0;
    while (zmq_send(sock_, frames[i].data(), frames[i].size(), flags) < 0) {
      if (zmq_errno() == EINTR) continue;
      if (zmq_errno() == EHOSTUNREACH || zmq_errno() == EAGAIN) return false;
      fail("send", endpoint_);
    }
  }
  return true;
}

bool ZmqSocket::receive(Frames& frames, int timeout_ms) {
  frames.clear();
  zmq_pollitem_t item{sock_, 0, ZMQ_POLLIN, 0};
  const int n = zmq_poll(&item, 1, timeout_ms);
  if (n < 0) {
    if (zmq_errno() == EINTR) return false;
    fail("poll", endpoint_);
  }
  if (n == 0) return false;
  int more = 1;
  while (more) {
    zmq_msg_t msg;
    zmq_msg_init(&msg);
    while (zmq_msg_recv(&msg, sock_, 0) < 0) {
      if (zmq_errno() != EINTR) {
        zmq_msg_close(&msg);
        fail("receive", endpoint_);
      }
    }
    frames.emplace_back(static_cast<const char*>(zmq_msg_data(&msg)), zmq_msg_size(&msg));
    more = zmq_msg_more(&msg);
    zmq_msg_close(&msg);
  }
  return true;
}

}  // namespace cosim::coupling
