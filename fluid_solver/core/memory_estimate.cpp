#include "fluid_solver/core/memory_estimate.h"

#include "fluid_solver/core/grid.h"

namespace cosim::fluid {

std::size_t estimated_state_bytes(const FluidScene& s) {
  const int np = s.num_phases(), dim = s.dim;
  const bool gran = np == 2 && s.exchange.dispersed && s.exchange.granular.enabled;
  const int cons = np * (2 + dim) + (np > 1 ? 1 : 0) + (gran ? 1 : 0);
  const int prim = np * (3 + dim) + (np > 1 ? 1 : 0) + (gran ? 1 : 0);
  double cells = 1.0;
  for (int d = 0; d < dim; ++d) cells *= s.cells[d] + 2.0 * Grid<3>::NG;
  const double bytes = cells * (3.0 * cons + prim) * sizeof(double);
  return bytes > 1e19 ? static_cast<std::size_t>(1e19) : static_cast<std::size_t>(bytes);
}

}  // namespace cosim::fluid
