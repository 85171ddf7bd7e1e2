// Boundary conditions (inflow, wall) and the heat-transfer source, against exact answers.
#include <gtest/gtest.h>

#include "common/exact/exact_riemann.h"
#include "fluid_solver/physics/drag_laws.h"
#include "fluid_test_utils.h"

namespace cosim::fluid::test {
namespace {

// A supersonic inflow (Mach 2.5) sweeps the domain: afterwards every cell holds the inflow state.
TEST(Boundaries, SupersonicInflowFillsDomain) {
  auto sim = run_scene(R"(
fluid:
  mesh: {cells: [100], lower: [0.0], upper: [1.0]}
  phases: [{name: gas, eos: {type: ideal_gas, gamma: 1.4}}]
  time: {end: 1.0}
  boundaries:
    x_lower: {type: inflow, state: {rho: 2.0, velocity: [3.0], p: 1.0}}
    x_upper: transmissive
  initial:
    state: {rho: 1.0, velocity: [0.0], p: 1.0}
)");
  PhaseFields f = sim->phase_fields(0);
  for (std::size_t i = 0; i < f.rho.size(); ++i) {
    EXPECT_NEAR(f.rho[i], 2.0, 1e-10) << i;
    EXPECT_NEAR(f.velocity[3 * i], 3.0, 1e-10) << i;
    EXPECT_NEAR(f.p[i], 1.0, 1e-10) << i;
  }
}

// Gas moving into a reflective wall: the reflected shock leaves the gas at rest with the star
// pressure of the symmetric Riemann problem (u, -u).
TEST(Boundaries, WallReflectsShockWithExactPressure) {
  for (const char* side : {"x_upper", "x_lower"}) {
    const double u = std::string(side) == "x_upper" ? 1.0 : -1.0;
    auto sim = run_scene(std::string(R"(
fluid:
  mesh: {cells: [400], lower: [0.0], upper: [1.0]}
  phases: [{name: gas, eos: {type: ideal_gas, gamma: 1.4}}]
  time: {end: 0.4}
  boundaries: {)") + side +
                         R"(: wall}
  initial:
    state: {rho: 1.0, velocity: [)" +
                         std::to_string(u) + R"(], p: 1.0}
)");
    exact::Star star = exact::solve_star({1, 1, 1}, {1.4, 0}, {1, -1, 1}, {1.4, 0});
    PhaseFields f = sim->phase_fields(0);
    const std::size_t probe = u > 0 ? 395 : 4;  // next to the wall, behind the reflected shock
    std::printf("wall at %s: p %.5f (exact %.5f), rho %.5f (exact %.5f), u %.2e\n", side, f.p[probe], star.p,
                f.rho[probe], star.rho_left, f.velocity[3 * probe]);
    EXPECT_NEAR(f.p[probe], star.p, 0.005 * star.p) << side;
    EXPECT_NEAR(f.velocity[3 * probe], 0.0, 1e-3) << side;
    // (the density next to a wall carries the usual wall-heating error of Godunov schemes)
    EXPECT_NEAR(f.rho[probe], star.rho_left, 0.05 * star.rho_left) << side;
  }
}

// Ranz-Marshall heat exchange between gas and particles at rest (no slip: Nu = 2): the
// temperature difference decays as exp(-t K (1/C_g + 1/C_p)), energy is conserved.
TEST(HeatTransfer, TemperatureDifferenceDecaysAtTheLawsRate) {
  FluidScene s = parse_fluid_scene(R"(
fluid:
  mesh: {cells: [4], lower: [0.0], upper: [0.01]}
  phases:
    - {name: gas, material: air}
    - {name: dust, material: tungsten}
  exchange: {velocity_relaxation: instant, pressure_relaxation: false, heat_transfer: ranz_marshall,
             particle_diameter: 1.0e-5, gas_conductivity: 0.026}
  time: {end: 1.0e-4}
  boundaries: {x_lower: periodic, x_upper: periodic}
  initial:
    state:
      p: 1.0e5
      alpha: [0.999, 0.001]
      phases: [{T: 1000}, {T: 300}]
)");
  auto sim = make_simulation(s);
  PhaseFields g0 = sim->phase_fields(0), p0 = sim->phase_fields(1);
  const double dT0 = g0.T[0] - p0.T[0];
  const double Cg = g0.alpha[0] * g0.rho[0] * s.phases[0].eos.cv, Cp = p0.alpha[0] * p0.rho[0] * s.phases[1].eos.cv;
  const double K = heat_exchange_coefficient(p0.alpha[0], g0.rho[0], 0.0, 1e-5, 1.8e-5, 0.026, 1.4 * 717.6);
  const double e0 = sim->totals()[0].energy + sim->totals()[1].energy;
  advance_to(*sim, s.t_end);
  const double dT = sim->phase_fields(0).T[0] - sim->phase_fields(1).T[0];
  const double expected = dT0 * std::exp(-s.t_end * K * (1 / Cg + 1 / Cp));
  std::printf("T_g - T_p: %.3f K -> %.4f K (law: %.4f K)\n", dT0, dT, expected);
  EXPECT_LT(expected, 0.5 * dT0);  // the exchange is visible in the test window
  EXPECT_NEAR(dT, expected, 0.01 * dT0);
  const double e1 = sim->totals()[0].energy + sim->totals()[1].energy;
  EXPECT_NEAR(e1, e0, 1e-13 * e0);
}

}  // namespace
}  // namespace cosim::fluid::test
