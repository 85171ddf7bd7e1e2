#include "fluid_solver/parallel/rank_plan.h"

#include <fmt/format.h>

#include <algorithm>

#include "common/parallel/decomposition.h"
#include "common/util/memory.h"
#include "fluid_solver/parallel/mesh_split.h"

namespace cosim::fluid {

std::string rank_plan(const FluidScene& scene, int ranks, double state_bytes, nlohmann::json& facts) {
  const parallel::Layout layout = fluid_layout(scene, ranks);
  long largest = 0, smallest = -1;
  parallel::Block biggest;
  for (int r = 0; r < layout.ranks(); ++r) {
    const parallel::Block b = parallel::block_of(layout, r, scene.cells);
    if (b.cells() > largest) largest = b.cells(), biggest = b;
    smallest = smallest < 0 ? b.cells() : std::min(smallest, b.cells());
  }
  double total = 1;
  for (int d = 0; d < scene.dim; ++d) total *= scene.cells[d];
  const double per_rank = state_bytes * static_cast<double>(largest) / total;
  std::string shape;
  for (int d = 0; d < scene.dim; ++d) shape += (d ? " x " : "") + std::to_string(biggest.upper[d] - biggest.lower[d]);
  facts["ranks"] = ranks;
  facts["layout"] = std::vector<int>(layout.blocks.begin(), layout.blocks.begin() + scene.dim);
  facts["cells_per_rank_max"] = largest;
  facts["cells_per_rank_min"] = smallest;
  facts["state_bytes_per_rank_max"] = per_rank;
  return fmt::format(
      "ranks: {}, layout {} ({}), the largest block {} cells ({}; the smallest {}), state about {} per "
      "rank",
      ranks, fmt::join(layout.blocks.begin(), layout.blocks.begin() + scene.dim, " x "),
      scene.parallel_ranks[0] > 0 ? "fluid.parallel.ranks" : "the least cut area", shape, largest, smallest,
      util::format_bytes(per_rank));
}

}  // namespace cosim::fluid
