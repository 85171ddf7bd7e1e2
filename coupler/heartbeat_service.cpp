#include "coupler/heartbeat_service.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>

#include "common/coupling/wire.h"
#include "coupler/owner_socket.h"

namespace cosim::coupler {

using coupling::Role;
namespace pb = coupling::pb;

namespace {
double now_s() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }
const std::array<Role, 2> kRoles{Role::Fluid, Role::Solid};
}  // namespace

HeartbeatService::HeartbeatService(coupling::ZmqContext& ctx, const std::string& endpoint, std::string token,
                                   double interval)
    : sock_(ctx, coupling::ZmqSocket::Type::Router), token_(std::move(token)), interval_(interval) {
  sock_.set_router_mandatory();
  sock_.set_max_message_size(4096);  // a heartbeat is a header: anything larger is dropped unread
  bound_ = bind_owner_only(sock_, endpoint);
  // The socket is the thread's from here on (a ZeroMQ socket is used by one thread at a time).
  thread_ = std::thread([this] { loop(); });
}

HeartbeatService::~HeartbeatService() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
  remove_socket_file(bound_);
}

void HeartbeatService::admit(Role r) { slot(r).admitted = true; }

std::string HeartbeatService::lost(Role r) const {
  std::lock_guard<std::mutex> lock(mutex_);
  return slot(r).lost;
}

void HeartbeatService::set_clock(long cycle, double time) {
  cycle_ = cycle;
  time_ = time;
}

void HeartbeatService::receive_one(const coupling::Frames& frames) {
  std::string why;
  const auto e = frames.size() == 2 ? coupling::decode(frames[1], why) : std::nullopt;
  const bool ours = e && e->has_heartbeat() && e->header().token() == token_ &&
                    (e->header().sender() == pb::ROLE_FLUID || e->header().sender() == pb::ROLE_SOLID);
  if (!ours) return;  // a stranger's: dropped unanswered
  Slot& s = slot(coupling::from_pb(e->header().sender()));
  if (!s.admitted) return;
  if (s.id.empty()) s.id = frames[0];
  if (s.id == frames[0]) s.last_heard = now_s();
}

void HeartbeatService::loop() {
  double next_beat = 0.0;
  coupling::Frames frames;
  while (!stop_) {
    const double t = now_s();
    if (t >= next_beat) {
      for (Role r : kRoles) {
        Slot& s = slot(r);
        if (s.id.empty()) continue;
        pb::Envelope e = coupling::make_envelope(Role::Coupler, token_, cycle_.load(), time_.load());
        e.mutable_heartbeat();
        // ROUTER_MANDATORY: an unroutable heartbeat means the solver's connection closed (its process is gone).
        try {
          if (!sock_.send({s.id, coupling::encode(e)}, 100)) {
            std::lock_guard<std::mutex> lock(mutex_);
            if (s.lost.empty()) s.lost = "its heartbeat connection closed";
          }
        } catch (const std::exception& ex) {
          std::lock_guard<std::mutex> lock(mutex_);
          if (s.lost.empty()) s.lost = fmt::format("its heartbeat connection failed: {}", ex.what());
        }
      }
      next_beat = t + interval_;
    }
    const int wait_ms = static_cast<int>(std::clamp((next_beat - now_s()) * 1e3, 1.0, 50.0));
    try {
      for (int w = wait_ms; sock_.receive(frames, w); w = 0) receive_one(frames);
    } catch (const std::exception&) {
      // a broken message from a stranger: dropped, the loop goes on
    }
  }
}

}  // namespace cosim::coupler
