// The passive wait every MPI call of common/parallel/mpi/ ends with (docs/parallel.md, "Waiting"): test the
// requests, sleep between tests once a few microseconds have passed; and the reductions both communicators
// (CartComm, GraphComm) make with it. Only for the sources of this folder.
#pragma once

#include <mpi.h>

#include <span>
#include <string>

#include "common/parallel/text_timing.h"

namespace cosim::parallel::detail {

void wait_passively(int count, MPI_Request* requests);

// On the communicator `comm` (an MPI_Comm*, as the communicators keep it), every rank together:
double max_over(void* comm, double local);            // the largest of every rank's `local`
void sum_over(void* comm, std::span<double> values);  // in place, every rank gets the sums (rank order)
void barrier_over(void* comm);
// Rank 0's text on every rank; `timing`, when given, gains the wait for the length and the transfer of the bytes.
std::string broadcast_over(void* comm, const std::string& from_root, TextTiming* timing = nullptr);

}  // namespace cosim::parallel::detail
