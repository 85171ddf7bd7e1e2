// The passive wait every MPI call of common/parallel/mpi/ ends with (docs/parallel.md, "Waiting"): test the
// requests, sleep between tests once a few microseconds have passed. Only for the sources of this folder.
#pragma once

#include <mpi.h>

namespace cosim::parallel::detail {

void wait_passively(int count, MPI_Request* requests);

}  // namespace cosim::parallel::detail
