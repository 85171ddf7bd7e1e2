// One rank's share of a partitioned solid mesh (mesh/partition.h) and what it reads from the others. Every rank
// holds the whole mesh and state arrays; a rank computes:
//   - the nodal update of the nodes it owns (partition.node_owner),
//   - the element update of every element touching one of those nodes (halo elements, computed redundantly by each
//     rank that needs them) and of the elements it owns (partition.element_part).
// A node's force is then the gather over its elements' corners in global element order, as on one rank, with every
// corner force computed here: no force or mass is summed across ranks, and the result is bit for bit the one-rank
// result. The nodes of those elements owned elsewhere (ghost nodes) get positions and velocities from their owners
// after every nodal update (the plan). Arithmetic only, no MPI: every rank computes the same parts.
#pragma once

#include <array>
#include <vector>

#include "common/parallel/graph_plan.h"
#include "solid_solver/mesh/mesh.h"
#include "solid_solver/mesh/partition.h"

namespace cosim::solid {

enum : char { kElementAbsent = 0, kElementOwned = 1, kElementHalo = 2 };

struct RankPart {
  int rank = 0, ranks = 1;
  std::vector<int> node_owner;     // per node (a node of no element: rank 0)
  std::vector<int> element_part;   // per element
  std::vector<int> owned_nodes;    // ascending
  std::vector<char> element_role;  // per element: kElementAbsent, kElementOwned or kElementHalo
  // Runs [begin, end) of consecutive elements with one role (owned or halo), ascending, none across a block border.
  struct Run {
    int begin, end;
    char role;
  };
  std::vector<Run> runs;
  parallel::GraphPlan ghosts;  // the ghost nodes, per neighbour rank
  int owned_elements = 0, halo_elements = 0;
};

// Rank `rank`'s part of partition p of mesh m.
RankPart make_rank_part(const Mesh& m, const MeshPartition& p, int rank);
// The part of a run on one rank (what make_rank_part gives for one part, without partitioning): everything owned.
RankPart whole_mesh_part(const Mesh& m);

}  // namespace cosim::solid
