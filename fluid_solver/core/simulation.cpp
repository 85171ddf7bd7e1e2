#include "fluid_solver/core/simulation.h"

#include <cmath>

namespace cosim::fluid {

std::unique_ptr<FluidSimulation> make_simulation_1d(const FluidScene& s);
std::unique_ptr<FluidSimulation> make_simulation_2d(const FluidScene& s);
std::unique_ptr<FluidSimulation> make_simulation_3d(const FluidScene& s);

std::unique_ptr<FluidSimulation> make_simulation(const FluidScene& s) {
  switch (s.dim) {
    case 1: return make_simulation_1d(s);
    case 2: return make_simulation_2d(s);
    case 3: return make_simulation_3d(s);
  }
  throw std::invalid_argument("fluid scene dimension must be 1, 2 or 3");
}

long advance_to(FluidSimulation& sim, double t_target) {
  long n = 0;
  const long max_steps = sim.scene().max_steps;
  while (sim.time() < t_target * (1.0 - 1e-14) && sim.steps() < max_steps) {
    double dt = sim.stable_dt();
    const double remaining = t_target - sim.time();
    if (dt >= remaining) dt = remaining;
    else if (dt > 0.5 * remaining) dt = 0.5 * remaining;  // avoid a tiny last step
    if (!(dt > 0.0) || !std::isfinite(dt)) throw StateError("time step collapsed (dt = " + std::to_string(dt) + ")");
    sim.advance(dt);
    ++n;
  }
  return n;
}

}  // namespace cosim::fluid
