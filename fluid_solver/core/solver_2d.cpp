// Instantiations of the 2D solvers (one translation unit per dimension keeps builds parallel).
#include "fluid_solver/core/embedded_bodies.h"
#include "fluid_solver/core/solver.h"

namespace cosim::fluid {

namespace {
std::unique_ptr<FluidSimulation> make_solver_2d(const FluidScene& s) {
  const bool two = s.num_phases() == 2;
  switch (s.flux) {
    case FluxKind::AUFS:
      if (two) return std::make_unique<Solver<2, 2, FluxKind::AUFS>>(s);
      return std::make_unique<Solver<2, 1, FluxKind::AUFS>>(s);
    case FluxKind::HLLC:
      if (two) return std::make_unique<Solver<2, 2, FluxKind::HLLC>>(s);
      return std::make_unique<Solver<2, 1, FluxKind::HLLC>>(s);
    case FluxKind::Rusanov:
      if (two) return std::make_unique<Solver<2, 2, FluxKind::Rusanov>>(s);
      return std::make_unique<Solver<2, 1, FluxKind::Rusanov>>(s);
  }
  return nullptr;
}
}  // namespace

std::unique_ptr<FluidSimulation> make_simulation_2d(const FluidScene& s) {
  auto sim = make_solver_2d(s);
  if (s.embedded.bodies.empty()) return sim;
  return std::make_unique<EmbeddedBodiesRun<2>>(std::move(sim), s);
}

}  // namespace cosim::fluid
