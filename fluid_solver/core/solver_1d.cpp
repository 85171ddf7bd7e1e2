// Instantiations of the 1D solvers (one translation unit per dimension keeps builds parallel).
#include "fluid_solver/core/solver.h"

namespace cosim::fluid {

std::unique_ptr<FluidSimulation> make_simulation_1d(const FluidScene& s) {
  const bool two = s.num_phases() == 2;
  switch (s.flux) {
    case FluxKind::AUFS:
      if (two) return std::make_unique<Solver<1, 2, FluxKind::AUFS>>(s);
      return std::make_unique<Solver<1, 1, FluxKind::AUFS>>(s);
    case FluxKind::HLLC:
      if (two) return std::make_unique<Solver<1, 2, FluxKind::HLLC>>(s);
      return std::make_unique<Solver<1, 1, FluxKind::HLLC>>(s);
    case FluxKind::Rusanov:
      if (two) return std::make_unique<Solver<1, 2, FluxKind::Rusanov>>(s);
      return std::make_unique<Solver<1, 1, FluxKind::Rusanov>>(s);
  }
  return nullptr;
}

}  // namespace cosim::fluid
