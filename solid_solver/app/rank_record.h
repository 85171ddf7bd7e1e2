// What the solid's runs on ranks share (rank_runner.cpp, the standalone run; coupled_runner.cpp, the coupled one):
// the threads per rank, the energy totals over the ranks and summary.json's "parallel" record.
#pragma once

#include <nlohmann/json.hpp>

#include "common/parallel/mpi/graph_comm.h"
#include "solid_solver/core/scene.h"
#include "solid_solver/core/simulation.h"
#include "solid_solver/mesh/rank_part.h"

namespace cosim::solid {

// Threads per rank when neither the scene, --threads nor OMP_NUM_THREADS chose: the cores of this rank's node shared
// by its ranks.
void set_threads_per_rank(const SolidScene& scene, const parallel::MpiSession& mpi);

// The energy budget summed over the ranks (every rank calls it; every rank gets the totals).
EnergyBudget energy_over_ranks(const Simulation& sim, const parallel::GraphComm& comm);

// summary.json's "parallel": ranks, the partition, each rank's elements (owned, halo), nodes (owned, ghost) and what
// it exchanged (every rank calls it).
nlohmann::json parallel_record(parallel::GraphComm& comm, const Simulation& sim, const RankPart& part, long cut_faces);

}  // namespace cosim::solid
