#include "common/util/progress.h"

#include <fmt/format.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>

namespace cosim::util {

Progress::Progress(bool enabled, double delay, double interval)
    : enabled_(enabled),
      tty_(isatty(2) != 0),
      delay_(delay),
      interval_(tty_ ? interval : 10.0),
      start_(std::chrono::steady_clock::now()) {}

double Progress::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

std::string format_duration(double s) {
  if (!(s >= 0) || !std::isfinite(s)) return "?";
  if (s < 59.5) return fmt::format("{:.0f}s", s);
  if (s < 3570) {  // whole seconds first, so that 3m59.7s is 4m00s and never 3m60s
    const long t = std::lround(s);
    return fmt::format("{}m{:02d}s", t / 60, static_cast<int>(t % 60));
  }
  const long m = std::lround(s / 60);
  return fmt::format("{}h{:02d}m", m / 60, static_cast<int>(m % 60));
}

void Progress::update(long step, double t, double t_end, const std::string& extra) {
  if (!enabled_) return;
  const double now = elapsed();
  if (now < delay_ || now - last_ < interval_) return;
  last_ = now;
  const double frac = t_end > 0 ? t / t_end : 1.0;
  const double eta = frac > 0 ? now * (1.0 - frac) / frac : 0.0;
  std::string line = fmt::format("step {}  t={:.6g}/{:.6g} ({:.1f}%)  {}  ETA {}", step, t, t_end, 100.0 * frac, extra,
                                 format_duration(eta));
  if (tty_) std::fprintf(stderr, "\r%-100s", line.c_str());
  else std::fprintf(stderr, "%s\n", line.c_str());
  std::fflush(stderr);
  shown_ = true;
}

void Progress::finish() {
  if (enabled_ && shown_ && tty_) std::fprintf(stderr, "\n");
}

}  // namespace cosim::util
