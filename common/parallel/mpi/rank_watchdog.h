// Liveness of the ranks of a run: a thread on each rank sends a heartbeat every half second on a communicator of its
// own (rank 0 to every rank, every rank to rank 0) and watches for the others'. A rank silent for longer than the
// timeout (stopped by SIGSTOP, hung in a system call, its node gone) is reported once, through `on_silence` on the
// rank that noticed it, which then ends the run (MPI_Abort): no rank waits forever for a rank that will not come.
// A rank that finishes says so before its heartbeats stop. Needs MPI_THREAD_MULTIPLE.
#pragma once

#include <functional>
#include <memory>
#include <string>

namespace cosim::parallel {

struct RankWatchdogState;

// How long a rank may be silent before the run is stopped: $COSIM_RANK_TIMEOUT seconds, else 2.5 s (with the
// launcher's clean-up, up to 2 s on a loaded machine, the run ends within 5 s of the stop).
double rank_silence_timeout();

class RankWatchdog {
 public:
  // on_silence(message, silent_rank, exit_code) runs on the watchdog thread before the run is aborted with
  // exit_code; it must not touch what the main thread is computing (write a file from what it is given).
  using OnSilence = std::function<void(const std::string& message, int silent_rank, int exit_code)>;
  RankWatchdog(double timeout_s, OnSilence on_silence);
  ~RankWatchdog();  // says this rank is leaving, then stops the thread
  RankWatchdog(const RankWatchdog&) = delete;
  RankWatchdog& operator=(const RankWatchdog&) = delete;

 private:
  std::unique_ptr<RankWatchdogState> state_;
};

}  // namespace cosim::parallel
