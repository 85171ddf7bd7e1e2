// How the launcher starts a solver on several MPI ranks.
#pragma once

#include <string>
#include <vector>

namespace cosim::launcher {

// The words that start `ranks` ranks of a program placed after them: srun inside a SLURM allocation (its
// environment names a job), else mpirun (with --allow-run-as-root for root, --oversubscribe when the ranks
// outnumber the cores, --bind-to none so each rank's threads may use the cores the machine gives it); nothing for
// one rank.
std::vector<std::string> rank_launcher(int ranks);

}  // namespace cosim::launcher
