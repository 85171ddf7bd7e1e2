// What every fluid run over the blocks of a split mesh does alike, standalone (block_runner.cpp) or coupled
// (coupled_runner.cpp): the layout and this rank's block set up with its links, the ranks agreed on a failure; what a
// rank that fails alone writes; and the whole mesh's figures for the summary.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "common/app/run_options.h"
#include "common/parallel/mpi/cart_comm.h"
#include "fluid_solver/app/run_summary.h"
#include "fluid_solver/core/scene.h"
#include "fluid_solver/core/simulation.h"
#include "fluid_solver/parallel/mesh_split.h"

namespace cosim::fluid {

struct FluidBlocks {
  std::unique_ptr<parallel::CartComm> comm;
  std::unique_ptr<CartBlockLinks> links;
  std::unique_ptr<FluidSimulation> sim;
};

// The scene's mesh over the ranks of `mpi` (one block without a launcher) and this rank's simulation of its block,
// linked to the others. Every rank calls it; the ranks agree on any rank's failure. 0, or the exit code (2) after the
// error is logged. Afterwards only rank 0 logs what every rank finds alike; the others their errors.
int set_up_blocks(const app::RunOptions& opt, const parallel::MpiSession& mpi, FluidScene& scene, FluidBlocks& out);

// Makes the output folder (rank 0; a failure ends every rank with 4) and clears an earlier run's summary, so that a
// failing rank's summary is the only one; every rank returns when the folder exists. 0, or 4 on one rank.
int prepare_output(const app::RunOptions& opt, const parallel::CartComm& comm);

// A failure on this rank alone (its exit code and message): its summary with this rank's figures, then every rank ends
// with the code (a rank interrupted by another's abort leaves that rank's summary).
[[noreturn]] void fail_alone(const app::RunOptions& opt, const FluidScene& scene, const FluidSimulation& sim,
                             const parallel::CartComm& comm, RunRecord& rec, int code, const std::string& error);

// The whole mesh's figures into the record (every rank together): totals, inflow, the embedded accounts, the wall time
// of the slowest rank, the ranks and their halo.
void record_over_blocks(RunRecord& rec, const FluidScene& scene, const FluidSimulation& sim,
                        const parallel::CartComm& comm);

// What a coupled fluid's rank-0 relay cost each rank (every rank together; docs/parallel.md "A coupled fluid on
// several ranks"): the broadcasts of what rank 0 received (`relayed`), the samples merged over the blocks
// (`samples`), the relay's encoding and decoding (`codec_s`), per rank in rank order; relay_s: the slowest rank's
// transfers and codec, the relay's own work, its waits apart.
nlohmann::json relay_over_blocks(const parallel::CartComm& comm, const parallel::TextTiming& relayed,
                                 const parallel::TextTiming& samples, double codec_s);

}  // namespace cosim::fluid
