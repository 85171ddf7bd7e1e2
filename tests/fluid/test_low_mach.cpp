// Low-Mach correction (paper eqs. 10-11): a Gresho vortex keeps more kinetic energy with it, and a
// shock tube is essentially unchanged by it.
#include <gtest/gtest.h>

#include "common/exact/exact_riemann.h"
#include "fluid_test_utils.h"

namespace cosim::fluid::test {
namespace {

double kinetic_energy(const FluidSimulation& sim) {
  PhaseFields f = sim.phase_fields(0);
  double k = 0;
  for (std::size_t c = 0; c < f.rho.size(); ++c)
    k += 0.5 * f.rho[c] * (f.velocity[3 * c] * f.velocity[3 * c] + f.velocity[3 * c + 1] * f.velocity[3 * c + 1]);
  return k;
}

double gresho_ke_kept(double mach, bool low_mach) {
  const std::string scene = R"(
fluid:
  mesh: {cells: [40, 40], lower: [0.0, 0.0], upper: [1.0, 1.0]}
  phases: [{name: gas, eos: {type: ideal_gas, gamma: 1.4}}]
  time: {end: 1.0}
  boundaries: {x_lower: periodic, x_upper: periodic, y_lower: periodic, y_upper: periodic}
  initial:
    profile: {type: gresho_vortex, center: [0.5, 0.5], speed: 1.0, mach: )" +
                            std::to_string(mach) + "}\n";
  FluidScene s = parse_fluid_scene(scene, {std::string("fluid.numerics.low_mach=") + (low_mach ? "true" : "false")});
  auto sim = make_simulation(s);
  const double k0 = kinetic_energy(*sim);
  advance_to(*sim, s.t_end);
  return kinetic_energy(*sim) / k0;
}

TEST(LowMachCorrection, GreshoVortexKeepsKineticEnergy) {
  for (double mach : {0.1, 0.02}) {
    const double plain = gresho_ke_kept(mach, false), corrected = gresho_ke_kept(mach, true);
    std::printf("Gresho M=%.2f, t=1: kinetic energy kept %.3f without, %.3f with the low-Mach correction\n", mach,
                plain, corrected);
    EXPECT_GT(corrected, plain + 0.15) << mach;
    EXPECT_GT(corrected, 0.9) << mach;
    EXPECT_LT(corrected, 1.0 + 1e-9) << mach;  // no spurious energy gain
  }
}

TEST(LowMachCorrection, ShockTubeUnchanged) {
  const int n = 400;
  exact::RiemannSolution ex({1, 0, 1}, {1.4, 0}, {0.125, 0, 0.1}, {1.4, 0});
  std::vector<double> r, u, p;
  exact::sample_on_cells(ex, 0.0, 1.0, n, 0.5, 0.2, r, u, p);
  double err[2];
  for (int lm = 0; lm < 2; ++lm) {
    auto sim = run_scene(riemann_scene(1, 0, 1, 0.125, 0, 0.1, 0.5, 0.2, n, lm ? "low_mach: true" : ""));
    err[lm] = l1_error(sim->phase_fields(0).rho, r);
  }
  std::printf("Sod N=400 L1(rho): %.3e without, %.3e with the low-Mach correction\n", err[0], err[1]);
  EXPECT_LT(err[1], 1.15 * err[0]);
}

}  // namespace
}  // namespace cosim::fluid::test
