#include "common/parallel/mpi/rank_watchdog.h"

#include <cstdlib>

#include <mpi.h>

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

namespace cosim::parallel {

namespace {
using Clock = std::chrono::steady_clock;
constexpr int kBeat = 1, kLeaving = 2;  // message tags
constexpr auto kInterval = std::chrono::milliseconds(500);
constexpr int kSilentCode = 5;  // a process of the run stopped answering (common/app/errors.h)
}  // namespace

struct RankWatchdogState {
  MPI_Comm comm = MPI_COMM_NULL;
  int rank = 0, size = 1;
  double timeout = 5;
  RankWatchdog::OnSilence on_silence;
  std::atomic<bool> stop{false};
  std::thread thread;
  std::vector<MPI_Request> sends;
  int token = 0;

  // The ranks this one watches: every other rank on rank 0, rank 0 elsewhere.
  bool watches(int r) const { return r != rank && (rank == 0 || r == 0); }

  void send_all(int tag) {
    for (int r = 0; r < size; ++r)
      if (watches(r)) {
        MPI_Request q;
        MPI_Isend(&token, 1, MPI_INT, r, tag, comm, &q);
        sends.push_back(q);
      }
    // Forget the sends that completed (a stopped receiver leaves its own pending: bounded by the timeout).
    std::vector<MPI_Request> open;
    for (MPI_Request& q : sends) {
      int done = 0;
      MPI_Test(&q, &done, MPI_STATUS_IGNORE);
      if (!done) open.push_back(q);
    }
    sends.swap(open);
  }

  void run() {
    std::vector<Clock::time_point> last(static_cast<std::size_t>(size), Clock::now());
    std::vector<char> gone(static_cast<std::size_t>(size), 0);
    auto next_beat = Clock::now(), previous = Clock::now();
    while (!stop) {
      const auto now = Clock::now();
      // This thread did not run for a while: this rank was the one stopped (SIGSTOP, then SIGCONT as the run is ended)
      // or starved. The others' heartbeats of that time are not theirs to miss: they are counted from now.
      if (now - previous > 2 * kInterval) std::fill(last.begin(), last.end(), now);
      previous = now;
      if (now >= next_beat) {
        send_all(kBeat);
        next_beat = now + kInterval;
      }
      for (int flag = 1; flag;) {  // every message that arrived
        MPI_Status st;
        MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, comm, &flag, &st);
        if (!flag) break;
        int v = 0;
        MPI_Recv(&v, 1, MPI_INT, st.MPI_SOURCE, st.MPI_TAG, comm, MPI_STATUS_IGNORE);
        last[static_cast<std::size_t>(st.MPI_SOURCE)] = Clock::now();
        if (st.MPI_TAG == kLeaving) gone[static_cast<std::size_t>(st.MPI_SOURCE)] = 1;
      }
      for (int r = 0; r < size; ++r) {
        if (!watches(r) || gone[static_cast<std::size_t>(r)]) continue;
        const double silent = std::chrono::duration<double>(Clock::now() - last[static_cast<std::size_t>(r)]).count();
        if (silent > timeout) {
          const std::string msg = fmt::format(
              "rank {} of {} has been silent for {:.1f} s (stopped, hung or its node lost; noticed by rank {}): the "
              "run is stopped",
              r, size, silent, rank);
          if (on_silence) on_silence(msg, r, kSilentCode);
          MPI_Abort(MPI_COMM_WORLD, kSilentCode);
        }
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    send_all(kLeaving);
  }
};

double rank_silence_timeout() {
  const char* v = std::getenv("COSIM_RANK_TIMEOUT");
  const double t = v ? std::atof(v) : 0.0;
  return t > 0 ? t : 2.5;
}

RankWatchdog::RankWatchdog(double timeout_s, OnSilence on_silence) {
  int initialised = 0, level = 0;
  MPI_Initialized(&initialised);
  if (!initialised) return;
  MPI_Query_thread(&level);
  if (level < MPI_THREAD_MULTIPLE) return;
  state_ = std::make_unique<RankWatchdogState>();
  MPI_Comm_dup(MPI_COMM_WORLD, &state_->comm);
  MPI_Comm_rank(state_->comm, &state_->rank);
  MPI_Comm_size(state_->comm, &state_->size);
  state_->timeout = timeout_s;
  state_->on_silence = std::move(on_silence);
  if (state_->size > 1) state_->thread = std::thread([s = state_.get()] { s->run(); });
}

RankWatchdog::~RankWatchdog() {
  if (!state_) return;
  state_->stop = true;
  if (state_->thread.joinable()) state_->thread.join();
  // Sends to a rank that has left may stay unmatched: released, not waited for.
  for (MPI_Request& q : state_->sends) {
    int done = 0;
    MPI_Test(&q, &done, MPI_STATUS_IGNORE);
    if (!done) MPI_Request_free(&q);
  }
  MPI_Comm_free(&state_->comm);
}

}  // namespace cosim::parallel
