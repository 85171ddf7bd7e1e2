#include "fluid_solver/parallel/mesh_split.h"

#include <fmt/format.h>

#include <stdexcept>

namespace cosim::fluid {

parallel::Layout fluid_layout(const FluidScene& scene, int ranks) {
  if (ranks > 1 && !scene.embedded.bodies.empty())
    throw std::invalid_argument(fmt::format(
        "{} ranks: a scene with embedded bodies runs on one rank for now (its bodies' geometry is not split yet)",
        ranks));
  if (ranks > 1 && scene.coupled)
    throw std::invalid_argument(
        fmt::format("{} ranks: a coupled fluid runs on one rank for now (the coupler serves one fluid process)", ranks));
  const parallel::Index3 cells = scene.cells;
  if (scene.parallel_ranks[0] > 0) {
    const parallel::Layout l{scene.parallel_ranks};
    if (auto problem = parallel::layout_problem(l, ranks, scene.dim, cells, kMinBlockCells))
      throw std::invalid_argument(fmt::format("fluid.parallel.ranks [{}]: {}",
                                              fmt::join(scene.parallel_ranks.begin(),
                                                        scene.parallel_ranks.begin() + scene.dim, ", "),
                                              *problem));
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

}  // namespace cosim::fluid
