// The standalone fluid run: scene -> snapshots at the output times -> summary.json.
#pragma once

#include "common/app/run_options.h"
#include "common/parallel/mpi/cart_comm.h"

namespace cosim::fluid {

using app::RunOptions;

// Exit codes: 0 success, 2 bad input (scene, options), 3 inadmissible state / numerical failure,
// 4 I/O failure, 130 interrupted.
// With opt.coupler set, run_fluid is the coupled run (coupled_runner.cpp): exit codes as above, plus 5 for a
// coupling failure (coupler lost, refused, protocol error).
// Under a parallel launcher (mpirun, srun) the standalone run splits the mesh over the ranks (run_fluid_blocks).
int run_fluid(const RunOptions& opt, const parallel::MpiSession& mpi);
int run_fluid_coupled(const RunOptions& opt, const parallel::MpiSession& mpi);
int run_fluid_blocks(const RunOptions& opt, const parallel::MpiSession& mpi);

}  // namespace cosim::fluid
