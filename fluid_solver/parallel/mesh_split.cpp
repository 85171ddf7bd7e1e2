#include "fluid_solver/parallel/mesh_split.h"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

namespace cosim::fluid {

parallel::Layout fluid_layout(const FluidScene& scene, int ranks) {
  const parallel::Index3 cells = scene.cells;
  if (scene.parallel_ranks[0] > 0) {
    const parallel::Layout l{scene.parallel_ranks};
    if (auto problem = parallel::layout_problem(l, ranks, scene.dim, cells, kMinBlockCells))
      throw std::invalid_argument(fmt::format(
          "fluid.parallel.ranks [{}]: {}",
          fmt::join(scene.parallel_ranks.begin(), scene.parallel_ranks.begin() + scene.dim, ", "), *problem));
    return l;
  }
  return parallel::choose_layout(ranks, scene.dim, cells, kMinBlockCells);
}

std::array<bool, 3> periodic_axes(const FluidScene& scene) {
  std::array<bool, 3> p{false, false, false};
  for (int d = 0; d < scene.dim; ++d) p[d] = scene.boundaries[d][0].kind == BoundaryKind::Periodic;
  return p;
}

void assign_block(FluidScene& scene, const parallel::CartComm& comm) {
  const parallel::Block& b = comm.block();
  MeshBlock& m = scene.block;
  for (int d = 0; d < 3; ++d) {
    m.first[d] = b.lower[d];
    m.count[d] = b.upper[d] - b.lower[d];
    for (int side = 0; side < 2; ++side) m.exchanged[d][side] = comm.neighbour(d, side) >= 0;
  }
}

CartBlockLinks::CartBlockLinks(parallel::CartComm& comm, const FluidScene& scene) : comm_(comm) {
  box_.dim = scene.dim;
  box_.ng = Grid<1>::NG;
  for (int d = 0; d < 3; ++d) box_.n[d] = scene.block.whole() ? scene.cells[d] : scene.block.count[d];
}

void CartBlockLinks::exchange_ghosts(FieldArray& W, int d) {
  vars_.resize(static_cast<std::size_t>(W.vars));
  for (int v = 0; v < W.vars; ++v) vars_[static_cast<std::size_t>(v)] = W.var(v);
  comm_.exchange_ghosts(vars_.data(), W.vars, box_, d);
}

const std::vector<std::size_t>& CartBlockLinks::plan_far(int channel, const std::vector<std::array<int, 3>>& cells) {
  // The owner of a cell: the block holding it, or for a cell outside the mesh (a ghost layer of the mesh's edge) the
  // block at that edge, whose ghost layer it is.
  const parallel::Layout& layout = comm_.layout();
  const parallel::Index3& mesh = comm_.cells();
  std::vector<int> owner(cells.size());
  std::vector<long> index(cells.size());
  for (std::size_t i = 0; i < cells.size(); ++i) {
    parallel::Index3 inside = cells[i];
    for (int d = 0; d < box_.dim; ++d) inside[d] = std::clamp(inside[d], 0, mesh[d] - 1);
    owner[i] = parallel::owner_of(layout, inside, mesh);
    const parallel::Block b = parallel::block_of(layout, owner[i], mesh);
    long at = 0, stride = 1;
    for (int d = 0; d < 3; ++d) {
      const int ng = d < box_.dim ? box_.ng : 0;
      const int padded = b.upper[d] - b.lower[d] + 2 * ng;
      const int local = cells[i][d] - b.lower[d] + ng;
      if (local < 0 || local >= padded)
        throw std::logic_error(fmt::format("cell {} along axis {} is not held by rank {}", cells[i][d], d, owner[i]));
      at += stride * local;
      stride *= padded;
    }
    index[i] = at;
  }
  parallel::SparsePlan& plan = far_plans_[static_cast<std::size_t>(channel)];
  plan = comm_.plan_sparse(owner, index);
  std::vector<std::size_t>& send = far_send_[static_cast<std::size_t>(channel)];
  send.assign(plan.send_index.begin(), plan.send_index.end());
  return send;
}

void CartBlockLinks::exchange_far(int channel, const double* send, double* recv, int width) {
  comm_.exchange_sparse(far_plans_[static_cast<std::size_t>(channel)], send, recv, width);
}

}  // namespace cosim::fluid
