// A progress line on stderr for long runs: silent for the first `delay` seconds, then refreshed
// at most every `interval` seconds ("\r" on a terminal, whole lines otherwise).
#pragma once

#include <chrono>
#include <string>

namespace cosim::util {

class Progress {
 public:
  explicit Progress(bool enabled, double delay = 2.0, double interval = 0.5);
  // fraction in [0,1]; extra is appended to the line (e.g. "dt=..., 12 Mcells/s").
  void update(long step, double t, double t_end, const std::string& extra);
  void finish();
  double elapsed() const;

 private:
  bool enabled_, tty_, shown_ = false;
  double delay_, interval_, last_ = -1e300;
  std::chrono::steady_clock::time_point start_;
};

std::string format_duration(double seconds);

}  // namespace cosim::util
