// The coupler's heartbeats on a thread of their own, with a socket of their own (Welcome.heartbeat_endpoint):
// while the coupler's main thread is busy (a large message, a checkpoint, the interface conditions of a big
// surface) its solvers still hear it, and it still hears them. The main thread asks, per solver, when it was
// last heard and whether its heartbeat connection has closed (the process is gone).
#pragma once

#include <array>
#include <atomic>
#include <mutex>
#include <string>
#include <thread>

#include "common/coupling/types.h"
#include "common/coupling/zmq_socket.h"

namespace cosim::coupler {

class HeartbeatService {
 public:
  // Binds `endpoint` (a ROUTER, owner-only ipc file) at once; beats every `interval` seconds to each admitted
  // solver. Heartbeats without `token`, or from a role not admitted, are dropped unanswered.
  HeartbeatService(coupling::ZmqContext& ctx, const std::string& endpoint, std::string token, double interval);
  ~HeartbeatService();
  HeartbeatService(const HeartbeatService&) = delete;
  HeartbeatService& operator=(const HeartbeatService&) = delete;

  const std::string& endpoint() const { return bound_; }  // as bound (tcp: the port chosen)
  // The solver of role `r` passed its Hello: its heartbeat connection is the first that beats for it.
  void admit(coupling::Role r);
  // Steady-clock seconds of its last heartbeat (0: none yet).
  double last_heard(coupling::Role r) const { return slot(r).last_heard.load(); }
  // Non-empty once its heartbeat connection is gone: what happened.
  std::string lost(coupling::Role r) const;
  // The cycle and time its heartbeats carry (informative).
  void set_clock(long cycle, double time);

 private:
  struct Slot {
    std::atomic<bool> admitted{false};
    std::atomic<double> last_heard{0.0};
    std::string id;    // routing id of its heartbeat connection (thread only)
    std::string lost;  // under mutex_
  };
  Slot& slot(coupling::Role r) { return slots_[r == coupling::Role::Fluid ? 0 : 1]; }
  const Slot& slot(coupling::Role r) const { return slots_[r == coupling::Role::Fluid ? 0 : 1]; }
  void loop();
  void receive_one(const coupling::Frames& frames);

  coupling::ZmqSocket sock_;
  std::string token_, bound_;
  double interval_;
  std::array<Slot, 2> slots_;
  std::atomic<long> cycle_{0};
  std::atomic<double> time_{0.0};
  std::atomic<bool> stop_{false};
  mutable std::mutex mutex_;
  std::thread thread_;
};

}  // namespace cosim::coupler
