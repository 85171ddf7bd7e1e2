#include "solid_solver/app/rank_plan.h"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

#include "common/util/memory.h"
#include "solid_solver/mesh/partition.h"
#include "solid_solver/mesh/rank_part.h"

namespace cosim::solid {

std::string solid_rank_plan(const SolidScene& scene, const Mesh& mesh, int ranks, double bytes_per_element,
                            nlohmann::json& facts) {
  if (ranks > 1 && !scene.ale.blocks.empty())
    throw std::invalid_argument(fmt::format("{} ranks: ALE blocks (solid.ale.blocks) run on one rank only", ranks));
  const MeshPartition p = partition_elements(mesh, ranks);
  int most = 0, fewest = mesh.num_elements, most_halo = 0;
  long most_ghosts = 0;
  for (int r = 0; r < ranks; ++r) {
    const RankPart part = make_rank_part(mesh, p, r);
    most = std::max(most, part.owned_elements);
    fewest = std::min(fewest, part.owned_elements);
    most_halo = std::max(most_halo, part.halo_elements);
    most_ghosts = std::max(most_ghosts, part.ghosts.received_items());
  }
  facts["ranks"] = ranks;
  facts["elements_per_rank_max"] = most;
  facts["elements_per_rank_min"] = fewest;
  facts["halo_elements_max"] = most_halo;
  facts["ghost_nodes_max"] = most_ghosts;
  // Every rank holds the whole mesh and state (the ranks share the work, not the memory: docs/parallel.md).
  return fmt::format(
      "ranks: {} (METIS parts, {} cut faces), owned elements {} to {} per rank, at most {} halo "
      "elements and {} ghost nodes on a rank, state about {} on every rank (each holds the whole mesh)",
      ranks, p.cut_faces, fewest, most, most_halo, most_ghosts,
      util::format_bytes(bytes_per_element * mesh.num_elements));
}

}  // namespace cosim::solid
