#include "solid_solver/app/rank_record.h"

#include <omp.h>

#include <algorithm>
#include <cstdlib>

namespace cosim::solid {

namespace {

// Per rank (index = rank) from each rank's own value: exact, every rank gets the list.
std::vector<double> per_rank(parallel::GraphComm& comm, double mine) {
  std::vector<double> v(static_cast<std::size_t>(comm.size()), 0.0);
  v[static_cast<std::size_t>(comm.rank())] = mine;
  comm.sum(v);
  return v;
}

}  // namespace

void set_threads_per_rank(const SolidScene& scene, const parallel::MpiSession& mpi) {
  if (scene.threads > 0) omp_set_num_threads(scene.threads);
  else if (mpi.size() > 1 && !std::getenv("OMP_NUM_THREADS"))
    omp_set_num_threads(std::max(1, omp_get_num_procs() / std::max(1, mpi.ranks_on_this_node())));
}

nlohmann::json parallel_record(parallel::GraphComm& comm, const Simulation& sim, const RankPart& part, long cut_faces) {
  const auto ints = [](const std::vector<double>& v) {
    std::vector<long> out;
    for (double x : v) out.push_back(static_cast<long>(x));
    return out;
  };
  std::vector<double> bytes{comm.halo_bytes()};
  comm.sum(bytes);
  const double halo_s = comm.max(comm.halo_seconds()), wait_s = comm.max(comm.halo_wait_seconds());
  std::vector<int> body_ranks;  // per rigid body, the ranks that own its nodes
  for (const RigidBody& rb : sim.rigid_bodies()) {
    std::vector<char> on(static_cast<std::size_t>(comm.size()), 0);
    for (int n : rb.nodes) on[static_cast<std::size_t>(part.node_owner[n])] = 1;
    body_ranks.push_back(static_cast<int>(std::count(on.begin(), on.end(), 1)));
  }
  return {{"ranks", comm.size()},
          {"layout", "metis"},
          {"partition", "METIS_PartMeshDual (contiguous parts, seed 1)"},
          {"cut_faces", cut_faces},
          {"elements_per_rank", ints(per_rank(comm, part.owned_elements))},
          {"halo_elements_per_rank", ints(per_rank(comm, part.halo_elements))},
          {"nodes_per_rank", ints(per_rank(comm, static_cast<double>(part.owned_nodes.size())))},
          {"ghost_nodes_per_rank", ints(per_rank(comm, static_cast<double>(part.ghosts.received_items())))},
          {"neighbours_per_rank", ints(per_rank(comm, static_cast<double>(part.ghosts.neighbours.size())))},
          {"threads_per_rank", omp_get_max_threads()},
          {"halo_bytes", bytes[0]},
          {"halo_seconds", halo_s},
          {"halo_wait_seconds", wait_s},
          {"rigid_body_ranks", body_ranks}};
}

EnergyBudget energy_over_ranks(const Simulation& sim, const parallel::GraphComm& comm) {
  EnergyBudget e = sim.energy();
  std::vector<double> v{e.internal, e.kinetic, e.boundary_work};
  comm.sum(v);
  e.internal = v[0];
  e.kinetic = v[1];
  e.boundary_work = v[2];
  return e;
}

}  // namespace cosim::solid
