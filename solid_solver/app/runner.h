// The standalone solid run: scene -> snapshots at the output times -> summary.json.
#pragma once

#include <memory>

#include "common/app/run_options.h"
#include "common/parallel/mpi/cart_comm.h"
#include "solid_solver/core/simulation.h"

namespace cosim::solid {

using app::RunOptions;

// Exit codes (as fluid_solver): 0 success, 2 bad input, 3 numerical failure, 4 I/O failure, 130 interrupted.
// With opt.coupler set, run_solid is the coupled run (coupled_runner.cpp; exit code 5: coupling failure).
// A standalone run is run_solid_ranks (one rank without a launcher).
int run_solid(const RunOptions& opt, const parallel::MpiSession& mpi);
// The coupled run, on one rank or over the ranks of an MPI launcher (docs/parallel.md, "A coupled solid on several
// ranks"): rank 0 talks to the coupler for every rank.
int run_solid_coupled(const RunOptions& opt, const parallel::MpiSession& mpi);
// The standalone run over the ranks of an MPI launcher, or alone (rank_runner.cpp; docs/parallel.md, "The solid on
// many ranks"); solid.checkpoint sets and --restart from them on any rank count.
int run_solid_ranks(const RunOptions& opt, const parallel::MpiSession& mpi);

// The first steps of every solid run: scene, threads, output directory (unless make_output is false: a rank that
// writes nothing), simulation. On failure (logged) sim is null and exit_code says why (2 bad input, 3 numerical
// failure, 4 I/O).
struct SolidRun {
  SolidScene scene;
  std::unique_ptr<Simulation> sim;
  int exit_code = 2;
};
// `load_mesh`: how a Gmsh mesh is read (scene.h; empty: read_gmsh on this process).
SolidRun prepare_solid_run(const RunOptions& opt, bool make_output = true, const MeshLoader& load_mesh = {});

}  // namespace cosim::solid
