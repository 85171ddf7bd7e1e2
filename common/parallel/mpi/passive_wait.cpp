#include "common/parallel/mpi/passive_wait.h"

#include <sched.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

namespace cosim::parallel::detail {

namespace {
MPI_Comm& as_comm(void* p) { return *static_cast<MPI_Comm*>(p); }
}  // namespace

// Waits for the requests: first testing them and yielding the core between tests (sched_yield, as OpenMPI's
// yield_when_idle) for up to kYieldFor: on a core of its own a rank sees the messages as they arrive, and with more
// ranks than cores a waiting rank hands its core to a rank that computes; then, for a long wait (a rank far behind,
// a slow file system), testing and sleeping between tests, 5 us growing to 100 us, so that a rank that waits long
// leaves its core entirely. Measured (docs/benchmarks.md): sleeping from the start cost 2 ranks at 250^2 cells each
// a third of their step; spinning costs 4 ranks on 2 cores 14%.
// COSIM_MPI_WAIT=spin tests without yielding or sleeping, COSIM_MPI_WAIT=sleep sleeps from the start (for the
// benchmark that compares them).
void wait_passively(int count, MPI_Request* requests) {
  enum class Mode { Passive, Spin, Sleep };
  static const Mode mode = [] {
    const char* v = std::getenv("COSIM_MPI_WAIT");
    const std::string s = v ? v : "";
    return s == "spin" ? Mode::Spin : s == "sleep" ? Mode::Sleep : Mode::Passive;
  }();
  constexpr auto kYieldFor = std::chrono::microseconds(200);
  int done = 0;
  if (mode == Mode::Spin) {
    while (!done) MPI_Testall(count, requests, &done, MPI_STATUSES_IGNORE);
    return;
  }
  MPI_Testall(count, requests, &done, MPI_STATUSES_IGNORE);
  if (done) return;
  if (mode == Mode::Sleep)
    for (int tests = 0; tests < 64 && !done; ++tests) MPI_Testall(count, requests, &done, MPI_STATUSES_IGNORE);
  if (done) return;
  if (mode == Mode::Passive) {
    const auto until = std::chrono::steady_clock::now() + kYieldFor;
    do {
      sched_yield();
      MPI_Testall(count, requests, &done, MPI_STATUSES_IGNORE);
      if (done) return;
    } while (std::chrono::steady_clock::now() < until);
  }
  auto pause = std::chrono::microseconds(mode == Mode::Sleep ? 2 : 5);
  while (true) {
    std::this_thread::sleep_for(pause);
    MPI_Testall(count, requests, &done, MPI_STATUSES_IGNORE);
    if (done) return;
    pause = std::min(pause * 2, std::chrono::microseconds(100));
  }
}

double max_over(void* comm, double local) {
  double out = local;
  MPI_Request r;
  MPI_Iallreduce(&local, &out, 1, MPI_DOUBLE, MPI_MAX, as_comm(comm), &r);
  wait_passively(1, &r);
  return out;
}

void sum_over(void* comm, std::span<double> values) {
  if (values.empty()) return;
  std::vector<double> in(values.begin(), values.end());
  MPI_Request r;
  MPI_Iallreduce(in.data(), values.data(), static_cast<int>(values.size()), MPI_DOUBLE, MPI_SUM, as_comm(comm), &r);
  wait_passively(1, &r);
}

void barrier_over(void* comm) {
  MPI_Request r;
  MPI_Ibarrier(as_comm(comm), &r);
  wait_passively(1, &r);
}

std::string broadcast_over(void* comm, const std::string& from_root, TextTiming* timing) {
  const auto t0 = std::chrono::steady_clock::now();
  int rank = 0;
  MPI_Comm_rank(as_comm(comm), &rank);
  // The length as the largest of rank 0's and the others' zeros: a reduction, so that the first stage ends on every
  // rank, rank 0 included, once every rank has come (the wait), and the second moves the bytes alone (the transfer).
  const long mine = rank == 0 ? static_cast<long>(from_root.size()) : 0;
  long n = 0;
  MPI_Request r;
  MPI_Iallreduce(&mine, &n, 1, MPI_LONG, MPI_MAX, as_comm(comm), &r);
  wait_passively(1, &r);
  const auto t1 = std::chrono::steady_clock::now();
  std::string out = rank == 0 ? from_root : std::string(static_cast<std::size_t>(n), '\0');
  constexpr long kChunk = 1L << 30;  // MPI counts are ints: a text of 2 GiB or more goes in pieces
  for (long at = 0; at < n; at += kChunk) {
    MPI_Ibcast(out.data() + at, static_cast<int>(std::min(kChunk, n - at)), MPI_CHAR, 0, as_comm(comm), &r);
    wait_passively(1, &r);
  }
  if (timing) {
    timing->wait_s += std::chrono::duration<double>(t1 - t0).count();
    timing->transfer_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
    timing->bytes += static_cast<double>(n);
    ++timing->calls;
  }
  return out;
}

}  // namespace cosim::parallel::detail
