// Background heartbeats of a client: a thread with its own DEALER connection to the coupler sends a Heartbeat
// every `interval` seconds and watches the coupler's; when nothing arrives for `timeout` seconds it marks the
// coupler lost. The data connection is untouched (no extra hop on the hot path).
#pragma once

#include <atomic>
#include <mutex>
#include <string>
#include <thread>

#include "common/coupling/types.h"
#include "common/coupling/zmq_socket.h"

namespace cosim::coupling {

class Heartbeat {
 public:
  Heartbeat(ZmqContext& ctx, std::string endpoint, Role role, std::string token, double interval, double timeout);
  ~Heartbeat();
  Heartbeat(const Heartbeat&) = delete;
  Heartbeat& operator=(const Heartbeat&) = delete;

  bool lost() const { return lost_.load(); }
  std::string lost_message() const;
  void stop();

 private:
  void loop();
  void declare_lost(const std::string& why);  // sets the message, then lost_

  ZmqContext& ctx_;
  std::string endpoint_, token_;
  Role role_;
  double interval_, timeout_;
  std::atomic<bool> stop_{false}, lost_{false};
  mutable std::mutex mutex_;
  std::string message_;
  std::thread thread_;
};

}  // namespace cosim::coupling
