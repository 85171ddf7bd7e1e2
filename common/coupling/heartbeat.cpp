#include "common/coupling/heartbeat.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>

#include "common/coupling/wire.h"

namespace cosim::coupling {

namespace {
double now_s() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

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
    sock.monitor_disconnections(monitor);
    ZmqSocket events(ctx_, ZmqSocket::Type::Pair);
    events.connect(monitor);
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
      for (Frames ev; events.receive(ev, 0);)
        if (ZmqSocket::is_disconnection(ev))
          return declare_lost(fmt::format("the coupler at {} closed the connection: its process has ended", endpoint_));
      const double silent = now_s() - last_seen;
      if (silent > timeout_)
        return declare_lost(fmt::format("coupler at {} declared dead: no heartbeat for {:.1f} s (timeout {:g} s)",
                                        endpoint_, silent, timeout_));
    }
  } catch (const std::exception& e) {
    declare_lost(fmt::format("heartbeat connection to the coupler at {} failed: {}", endpoint_, e.what()));
  }
}

void Heartbeat::declare_lost(const std::string& why) {
  std::lock_guard<std::mutex> lock(mutex_);
  message_ = why;
  lost_ = true;
}

}  // namespace cosim::coupling
