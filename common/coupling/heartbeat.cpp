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
