// Sedov-Taylor blast (docs/methods.md §8.3) on Lagrangian meshes: shock radius within 3% of
// R = (E t^2 / (alpha rho0))^(1/(nu+2)) (measured at the density peak) and total energy (internal + kinetic) conserved
// to round-off.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>

#include "solid_test_util.h"

using namespace cosim::solid;

namespace {
void check_sedov(Simulation& sim, double E_full, double alpha, int nu, double h, double t_end) {
  const double e0 = sim.energy().total();
  solid_test::run_to(sim, t_end);
  const double R_exact = std::pow(E_full * t_end * t_end / alpha, 1.0 / (nu + 2));
  const double R = solid_test::shock_radius_peak(sim, h, 1.0);
  const double R_half = solid_test::shock_radius_half_max(sim, h, 1.0);
  const auto e = sim.energy();
  const double drift = (e.total() - e0 - e.boundary_work) / e0;
  std::printf(
      "[ measured ] Sedov nu=%d: %ld steps, shock radius (density peak) %.4f vs %.4f (%.2f%%), "
      "half-max front %.4f, energy drift %.2e\n",
      nu, sim.steps(), R, R_exact, 100 * (R - R_exact) / R_exact, R_half, drift);
  EXPECT_NEAR(R / R_exact, 1.0, 0.03);
  EXPECT_LT(std::abs(drift), 1e-6);
  EXPECT_LT(std::abs(e.boundary_work / e0), 1e-10);  // symmetry planes do no work
}
}  // namespace

// Cylindrical, gamma = 1.4, alpha = 0.984074: quarter plane, E per unit length alpha -> R(1) = 1.
TEST(SolidSedov, Cylindrical2D) {
  const double alpha = 0.984074;
  SolidScene s = parse_solid_scene(fmt::format(R"(
solid:
  mesh: {{cells: [60, 60], lower: [0, 0], upper: [1.2, 1.2]}}
  blocks:
    - {{name: gas, eos: {{type: ideal_gas, gamma: 1.4}}, density: 1.0}}
  initial:
    energy_deposits: [{{point: [0, 0], energy: {}}}]
  boundaries:
    - {{set: x_lower, type: symmetry}}
    - {{set: y_lower, type: symmetry}}
  time: {{end: 1.0}}
)",
                                               alpha / 4));
  Simulation sim(s);
  check_sedov(sim, alpha, alpha, 2, 0.02, 1.0);
}

// The shipped LULESH scene: spherical, gamma = 5/3, alpha = 0.493590, octant, 8 x 616.99 J -> R(0.01) = 1.
TEST(SolidSedov, Spherical3DLuleshScene) {
  SolidScene s = load_solid_scene(std::string(COSIM_SOURCE_DIR) + "/configs/solid_sedov_lulesh.yaml",
                                  {"solid.mesh.cells=[24,24,24]"});
  Simulation sim(s);
  check_sedov(sim, 8 * 616.99, 0.493590, 3, 1.125 / 24, 0.01);
}
