// Instantiations of the 3D solvers (one translation unit per dimension keeps builds parallel).
#include "fluid_solver/core/embedded_bodies.h"
#include "fluid_solver/core/solver.h"

namespace cosim::fluid {

namespace {
std::unique_ptr<FluidSimulation> make_solver_3d(const FluidScene& s) {
  const bool two = s.num_phases() == 2;
  switch (s.flux) {
    case FluxKind::AUFS:
      if (two) return std::make_unique<Solver<3, 2, FluxKind::AUFS>>(s);
      return std::make_unique<Solver<3, 1, FluxKind::AUFS>>(s);
    case FluxKind::HLLC:
      if (two) return std::make_unique<Solver<3, 2, FluxKind::HLLC>>(s);
      return std::make_unique<Solver<3, 1, FluxKind::HLLC>>(s);
    case FluxKind::Rusanov:
      if (two) return std::make_unique<Solver<3, 2, FluxKind::Rusanov>>(s);
      return std::make_unique<Solver<3, 1, FluxKind::Rusanov>>(s);
  }
  return nullptr;
}
}  // namespace

std::unique_ptr<FluidSimulation> make_simulation_3d(const FluidScene& s) {
  auto sim = make_solver_3d(s);
  if (s.embedded.bodies.empty()) return sim;
  return std::make_unique<EmbeddedBodiesRun<3>>(std::move(sim), s);
}

}  // namespace cosim::fluid
