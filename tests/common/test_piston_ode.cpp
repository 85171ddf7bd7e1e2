// Two-chamber piston reference ODE (docs/methods.md §8.2): equilibrium, turning points and period of the
// nondimensional setup (A = m = pR0 = 1, VL0 = 1, VR0 = 2, pL0 = 2) against the reference numbers there.
#include <gtest/gtest.h>

#include <cmath>

#include "common/verification/piston_ode.h"

using namespace cosim::verification;

TEST(PistonOde, AdiabaticTwoChamberMatchesReference) {
  PistonOde p;  // defaults: the nondimensional setup, gamma = 1.4
  const auto eq = piston_equilibrium(p);
  EXPECT_NEAR(eq.v_left, 1.35195, 1e-5);
  EXPECT_NEAR(eq.v_right, 1.64805, 1e-5);
  EXPECT_NEAR(eq.pressure, 1.31125, 1e-5);
  EXPECT_NEAR(eq.x_eq, 0.35195, 1e-5);
  EXPECT_NEAR(2 * M_PI / eq.omega, 3.996, 1e-3);
  EXPECT_NEAR(piston_acceleration(p, eq.x_eq), 0.0, 1e-12);
  const auto tr = integrate_piston(p, 20.0, 1e-3);
  EXPECT_NEAR(tr.x_min(), 0.0, 1e-9);
  EXPECT_NEAR(tr.x_max(), 0.7177, 1e-4);
  EXPECT_NEAR(tr.period(), 3.878, 1e-3);
  // Hermite interpolation between samples and step-size convergence.
  const auto fine = integrate_piston(p, 20.0, 2.5e-4);
  for (double t : {0.1234, 1.9, 7.77, 13.3}) EXPECT_NEAR(tr.x_at(t), fine.x_at(t), 1e-9) << t;
}

TEST(PistonOde, IsothermalAndScaling) {
  PistonOde p;
  p.gamma = 1.0;
  const auto eq = piston_equilibrium(p);
  EXPECT_NEAR(eq.v_left, 1.5, 1e-12);
  EXPECT_NEAR(eq.pressure, 4.0 / 3.0, 1e-12);
  const auto tr = integrate_piston(p, 20.0, 1e-3);
  EXPECT_NEAR(tr.x_max(), 1.0, 1e-6);
  EXPECT_NEAR(tr.period(), 4.511, 1e-3);
  // Dimensional: time scales with sqrt(m L / (A pR0)); extra mass lengthens the period by sqrt((m+me)/m).
  PistonOde d;
  d.mass = 100.0;
  d.p_left = 2e5;
  d.p_right = 1e5;
  const double T0 = integrate_piston(d, 1.0, 1e-5).period();
  EXPECT_NEAR(T0, 3.878 * std::sqrt(100.0 / 1e5), 1e-3 * T0);
  d.extra_mass = 1.0;
  EXPECT_NEAR(integrate_piston(d, 1.0, 1e-5).period() / T0, std::sqrt(101.0 / 100.0), 1e-5);
}
