#include "common/coupling/heartbeat.h"

#include <fmt/format.h>
#include <zmq.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstring>

#include "common/coupling/wire.h"

namespace cosim::coupling {

namespace {
double now_s() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

// True when the monitor socket holds a disconnection event (frame 1: uint16 event, uint32 value; frame 2: the
// endpoint).
bool disconnected(void* events) {
  bool seen = false;
  for (;;) {
    zmq_msg_t msg;
    zmq_msg_init(&msg);
    if (zmq_msg_recv(&msg, events, ZMQ_DONTWAIT) < 0) {
      zmq_msg_close(&msg);
      return seen;
    }
    std::uint16_t event = 0;
    if (zmq_msg_size(&msg) >= sizeof event && zmq_msg_more(&msg)) {
      std::memcpy(&event, zmq_msg_data(&msg), sizeof event);
      seen = seen || event == ZMQ_EVENT_DISCONNECTED;
    }
    zmq_msg_close(&msg);
  }
}
}  // namespace

Heartbeat::Heartbeat(ZmqContext& ctx, std::string endpoint, Role role, std::string token, double interval,
                     double timeout)
    : ctx_(ctx),
      endpoint_(std::move(endpoint)),
      token_(std::move(token)),
      role_(role),
      interval_(interval),
      timeout_(timeout),
      thread_([this] { loop(); }) {}

Heartbeat::~Heartbeat() { stop(); }

void Heartbeat::stop() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
}

std::string Heartbeat::lost_message() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return message_;
}

void Heartbeat::loop() {
  try {
    ZmqSocket sock(ctx_, ZmqSocket::Type::Dealer);
    // A coupler whose process has ended closes its end of the connection: the socket monitor reports the
    // disconnection at once, where the silence would take the whole timeout.
    const std::string monitor = fmt::format("inproc://heartbeat-monitor-{}", static_cast<const void*>(this));
    zmq_socket_monitor(sock.handle(), monitor.c_str(), ZMQ_EVENT_DISCONNECTED);
    void* events = zmq_socket(ctx_.get(), ZMQ_PAIR);
    zmq_connect(events, monitor.c_str());
    struct Close {
      void* sock;
      void* events;
      ~Close() {
        zmq_socket_monitor(sock, nullptr, 0);
        int zero = 0;
        zmq_setsockopt(events, ZMQ_LINGER, &zero, sizeof zero);
        zmq_close(events);
      }
    } close_monitor{sock.handle(), events};
    sock.connect(endpoint_);
    double last_seen = now_s(), next_send = 0.0;
    Frames frames;
    while (!stop_) {
      const double t = now_s();
      if (t >= next_send) {
        pb::Envelope e = make_envelope(role_, token_, 0, 0.0);
        e.mutable_heartbeat();
        sock.send({encode(e)}, 100);
        next_send = t + interval_;
      }
      const int wait_ms = static_cast<int>(std::clamp((next_send - t) * 1e3, 1.0, 50.0));
      for (int w = wait_ms; sock.receive(frames, w); w = 0) last_seen = now_s();  // any message counts
      if (disconnected(events)) {
        std::lock_guard<std::mutex> lock(mutex_);
        message_ = fmt::format("the coupler at {} closed the connection: its process has ended", endpoint_);
        lost_ = true;
        return;
      }
      const double silent = now_s() - last_seen;
      if (silent > timeout_) {
        std::lock_guard<std::mutex> lock(mutex_);
        message_ = fmt::format("coupler at {} declared dead: no heartbeat for {:.1f} s (timeout {:g} s)", endpoint_,
                               silent, timeout_);
        lost_ = true;
        return;
      }
    }
  } catch (const std::exception& e) {
    std::lock_guard<std::mutex> lock(mutex_);
    message_ = fmt::format("heartbeat connection to the coupler at {} failed: {}", endpoint_, e.what());
    lost_ = true;
  }
}

}  // namespace cosim::coupling
