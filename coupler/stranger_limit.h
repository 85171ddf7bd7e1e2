// Traffic from connections that are not the run's solvers (garbage, strangers' Hellos, messages before Hello):
// each gets an Error reply and a log line, so a flood would slow the run and fill its log. A token bucket admits
// kRate of them per second (bursts of kBurst); the rest are dropped unanswered and only counted, with one summary
// line at most every kSummaryEvery seconds; after kMaxLogged named lines the log only carries the summaries.
#pragma once

#include <algorithm>
#include <string>

#include <fmt/format.h>

namespace cosim::coupler {

class StrangerLimit {
 public:
  static constexpr double kRate = 20, kBurst = 40, kSummaryEvery = 10;
  static constexpr long kMaxLogged = 200;

  // True when the message that arrived at `now` [s] may be answered; `log` then says whether to name it.
  bool admit(double now, bool& log) {
    tokens_ = std::min(kBurst, tokens_ + (now - last_) * kRate);
    last_ = now;
    if (tokens_ < 1) {
      ++dropped_;
      log = false;
      return false;
    }
    tokens_ -= 1;
    log = logged_ < kMaxLogged;
    if (log) ++logged_;
    else ++unlogged_;
    return true;
  }

  // The line to log at `now`, or "": what was dropped or answered without a line since the last summary.
  std::string summary(double now) {
    if ((dropped_ == 0 && unlogged_ == 0) || now - last_summary_ < kSummaryEvery) return "";
    const std::string s = fmt::format(
        "unknown connections: {} message(s) dropped unanswered (more than {:g} per second), {} answered without a "
        "log line, in the last {:.0f} s",
        dropped_, kRate, unlogged_, now - last_summary_);
    total_dropped_ += dropped_;
    dropped_ = unlogged_ = 0;
    last_summary_ = now;
    return s;
  }
  long dropped() const { return total_dropped_ + dropped_; }

 private:
  double tokens_ = kBurst, last_ = 0, last_summary_ = 0;
  long dropped_ = 0, unlogged_ = 0, logged_ = 0, total_dropped_ = 0;
};

}  // namespace cosim::coupler
