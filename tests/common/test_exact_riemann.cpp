// Tests of the exact Riemann solver against docs/methods.md §8.1 (Toro ch. 4 tables) and against the
// jump conditions / isentropes it must satisfy.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <vector>

#include "common/exact/exact_riemann.h"

namespace {

using cosim::exact::Material;
using cosim::exact::Primitive;
using cosim::exact::RiemannSolution;
using cosim::exact::sample_on_cells;
using cosim::exact::solve_star;
using cosim::exact::Star;

const Material kAir{1.4, 0.0};
const Material kWater{4.4, 6.0e8};

// Tolerance for a value printed with `decimals` digits after the point: half a unit of the last
// digit (slightly widened) or 2e-5 relative, whichever is larger.
double table_tol(double ref, int decimals) { return std::max(0.51 * std::pow(10.0, -decimals), 2e-5 * std::abs(ref)); }

struct ToroCase {
  const char* name;
  Primitive L, R;
  double p, u, rhoL, rhoR;
  int dp, du, drho;  // printed decimals of p*, u*, rho*
};

// docs/methods.md §8.1, Toro's exact-solver test set (gamma = 1.4).
// clang-format off
const ToroCase kToro[] = {
    {"sod", {1, 0, 1}, {0.125, 0, 0.1}, 0.30313, 0.92745, 0.42632, 0.26557, 5, 5, 5},
    {"123", {1, -2, 0.4}, {1, 2, 0.4}, 0.00189, 0.00000, 0.02185, 0.02185, 5, 5, 5},
    {"left_blast", {1, 0, 1000}, {1, 0, 0.01}, 460.894, 19.5975, 0.57506, 5.99924, 3, 4, 5},
    {"right_blast", {1, 0, 0.01}, {1, 0, 100}, 46.0950, -6.19633, 5.99242, 0.57511, 4, 5, 5},
    {"shock_collision", {5.99924, 19.5975, 460.894}, {5.99242, -6.19633, 46.0950},
     1691.64, 8.68975, 14.2823, 31.0426, 2, 5, 4},
    // Toro's numerical-scheme Test 1 (modified Sod with u_L = 0.75).
    {"sod_modified", {1, 0.75, 1}, {0.125, 0, 0.1}, 0.46629, 1.36091, 0.57987, 0.33970, 5, 5, 5},
};
// clang-format on

// Specific enthalpy of the stiffened gas, h = gamma (p + pinf) / ((gamma - 1) rho)
// (docs/methods.md §7.2).
double enthalpy(double rho, double p, const Material& m) { return m.gamma * (p + m.pinf) / ((m.gamma - 1.0) * rho); }
double sound_speed(double rho, double p, const Material& m) { return std::sqrt(m.gamma * (p + m.pinf) / rho); }

// Checks that the wave of side `side` (-1 left, +1 right) connects the initial state to the star
// state: Rankine-Hugoniot for a shock, isentrope + Riemann invariant for a rarefaction.
void check_wave(const RiemannSolution& s, int side, double rel) {
  const Primitive& K = side < 0 ? s.left_state() : s.right_state();
  const Material& m = side < 0 ? s.left_material() : s.right_material();
  const Star& st = s.star();
  const double rho_s = side < 0 ? st.rho_left : st.rho_right;
  const double head = side < 0 ? s.left_head() : s.right_head();
  const double tail = side < 0 ? s.left_tail() : s.right_tail();
  const double pscale = std::max(std::abs(K.p), std::abs(st.p)) + m.pinf;
  if (st.p > K.p) {
    ASSERT_EQ(head, tail);
    const double S = head;
    const double w0 = K.u - S, w1 = st.u - S;  // velocities relative to the shock
    const double mflux = K.rho * w0;
    EXPECT_NEAR(rho_s * w1, mflux, rel * std::abs(mflux)) << "mass";
    EXPECT_NEAR(st.p + rho_s * w1 * w1, K.p + K.rho * w0 * w0, rel * pscale) << "momentum";
    const double h0 = enthalpy(K.rho, K.p, m) + 0.5 * w0 * w0;
    const double h1 = enthalpy(rho_s, st.p, m) + 0.5 * w1 * w1;
    EXPECT_NEAR(h1, h0, rel * std::abs(h0)) << "energy";
  } else {
    const double s0 = (K.p + m.pinf) / std::pow(K.rho, m.gamma);
    const double s1 = (st.p + m.pinf) / std::pow(rho_s, m.gamma);
    EXPECT_NEAR(s1, s0, rel * s0) << "isentrope";
    // Generalised Riemann invariant u -+ 2c/(gamma-1) across the left/right fan.
    const double sgn = side < 0 ? 1.0 : -1.0;
    const double j0 = K.u + sgn * 2.0 * sound_speed(K.rho, K.p, m) / (m.gamma - 1.0);
    const double j1 = st.u + sgn * 2.0 * sound_speed(rho_s, st.p, m) / (m.gamma - 1.0);
    EXPECT_NEAR(j1, j0, rel * (std::abs(j0) + sound_speed(K.rho, K.p, m)));
    // Inside the fan the characteristic through the origin is xi = u -+ c.
    if (tail - head > 1e-9 * (std::abs(head) + std::abs(tail))) {
      const double xi = 0.5 * (head + tail);
      const auto q = s.sample(xi);
      EXPECT_NEAR(q.u - sgn * sound_speed(q.rho, q.p, m), xi, 1e-12 * (std::abs(xi) + 1.0));
      EXPECT_NEAR((q.p + m.pinf) / std::pow(q.rho, m.gamma), s0, 1e-12 * s0);
      EXPECT_EQ(q.side, side);
    }
  }
}

void check_mirror(const Primitive& L, const Material& mL, const Primitive& R, const Material& mR) {
  const RiemannSolution a(L, mL, R, mR);
  const RiemannSolution b({R.rho, -R.u, R.p}, mR, {L.rho, -L.u, L.p}, mL);
  const double ps = std::max(std::abs(a.star().p), std::max(L.p + mL.pinf, R.p + mR.pinf));
  const double us = std::max({std::abs(L.u), std::abs(R.u), std::abs(a.star().u), 1.0});
  EXPECT_EQ(a.star().vacuum, b.star().vacuum);
  EXPECT_NEAR(b.star().p, a.star().p, 1e-12 * ps);
  EXPECT_NEAR(b.star().u, -a.star().u, 1e-12 * us);
  EXPECT_NEAR(b.star().rho_left, a.star().rho_right, 1e-11 * a.star().rho_right);
  EXPECT_NEAR(b.star().rho_right, a.star().rho_left, 1e-11 * a.star().rho_left);
  EXPECT_NEAR(b.left_head(), -a.right_head(), 1e-12 * us);
  EXPECT_NEAR(b.left_tail(), -a.right_tail(), 1e-12 * us);
  EXPECT_NEAR(b.contact(), -a.contact(), 1e-12 * us);
  EXPECT_NEAR(b.right_tail(), -a.left_tail(), 1e-12 * us);
  EXPECT_NEAR(b.right_head(), -a.left_head(), 1e-12 * us);
  // Sample on a grid of xi spanning all the waves (points at exact wave positions skipped).
  const double span = 1.5 * std::max(std::abs(a.left_head()), std::abs(a.right_head()));
  const std::vector<double> waves = {a.left_head(), a.left_tail(), a.contact(), a.right_tail(), a.right_head()};
  for (int i = 0; i <= 400; ++i) {
    const double xi = -span + 2.0 * span * (i + 0.31) / 400.0;
    bool near_wave = false;
    for (double w : waves) near_wave = near_wave || std::abs(xi - w) < 1e-9 * span;
    if (near_wave) continue;
    const auto qa = a.sample(xi);
    const auto qb = b.sample(-xi);
    const double rs = std::max(L.rho, R.rho);
    EXPECT_NEAR(qb.rho, qa.rho, 1e-11 * rs) << "xi = " << xi;
    EXPECT_NEAR(qb.u, -qa.u, 1e-11 * us) << "xi = " << xi;
    EXPECT_NEAR(qb.p, qa.p, 1e-11 * ps) << "xi = " << xi;
    EXPECT_EQ(qb.side, -qa.side) << "xi = " << xi;
  }
}

TEST(ExactRiemann, ToroStarStates) {
  for (const auto& c : kToro) {
    SCOPED_TRACE(c.name);
    const Star s = solve_star(c.L, kAir, c.R, kAir);
    EXPECT_FALSE(s.vacuum);
    EXPECT_NEAR(s.p, c.p, table_tol(c.p, c.dp));
    EXPECT_NEAR(s.u, c.u, table_tol(c.u, c.du));
    EXPECT_NEAR(s.rho_left, c.rhoL, table_tol(c.rhoL, c.drho));
    EXPECT_NEAR(s.rho_right, c.rhoR, table_tol(c.rhoR, c.drho));
  }
}

TEST(ExactRiemann, ToroJumpConditionsToRoundoff) {
  for (const auto& c : kToro) {
    SCOPED_TRACE(c.name);
    const RiemannSolution s(c.L, kAir, c.R, kAir);
    check_wave(s, -1, 1e-11);
    check_wave(s, +1, 1e-11);
  }
}

TEST(ExactRiemann, SodSamplesAtT02) {
  const RiemannSolution s({1, 0, 1}, kAir, {0.125, 0, 0.1}, kAir);
  const double t = 0.2, x0 = 0.5;
  // docs/methods.md §8.1 wave positions and shock speed.
  EXPECT_NEAR(x0 + t * s.left_head(), 0.26336, 6e-6);
  EXPECT_NEAR(x0 + t * s.left_tail(), 0.48595, 6e-6);
  EXPECT_NEAR(x0 + t * s.contact(), 0.68549, 6e-6);
  EXPECT_NEAR(x0 + t * s.right_head(), 0.85043, 6e-6);
  EXPECT_EQ(s.right_tail(), s.right_head());
  EXPECT_NEAR(s.right_head(), 1.75216, 6e-6);

  const double xs[] = {0.1, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9};
  const double rho[] = {1.00000, 0.87745, 0.60294, 0.42632, 0.42632, 0.26557, 0.26557, 0.12500};
  const double u[] = {0, 0.15268, 0.56935, 0.92745, 0.92745, 0.92745, 0.92745, 0};
  const double p[] = {1.00000, 0.83275, 0.49247, 0.30313, 0.30313, 0.30313, 0.30313, 0.10000};
  const int side[] = {-1, -1, -1, -1, -1, +1, +1, +1};
  for (int i = 0; i < 8; ++i) {
    SCOPED_TRACE(xs[i]);
    const auto q = s.sample((xs[i] - x0) / t);
    EXPECT_NEAR(q.rho, rho[i], 6e-6);
    EXPECT_NEAR(q.u, u[i], 6e-6);
    EXPECT_NEAR(q.p, p[i], 6e-6);
    EXPECT_EQ(q.side, side[i]);
  }

  // Same through sample_on_cells: 9 cells of width 0.1 centred at 0.1, 0.2, ..., 0.9.
  std::vector<double> r, v, pr;
  sample_on_cells(s, 0.05, 0.95, 9, x0, t, r, v, pr);
  ASSERT_EQ(r.size(), 9u);
  ASSERT_EQ(v.size(), 9u);
  ASSERT_EQ(pr.size(), 9u);
  EXPECT_DOUBLE_EQ(r[1], 1.0);  // x = 0.2 is ahead of the rarefaction head
  for (int i = 0; i < 8; ++i) {
    const int cell = i == 0 ? 0 : i + 1;
    SCOPED_TRACE(xs[i]);
    EXPECT_NEAR(r[cell], rho[i], 6e-6);
    EXPECT_NEAR(v[cell], u[i], 6e-6);
    EXPECT_NEAR(pr[cell], p[i], 6e-6);
  }

  // t = 0 returns the initial data.
  sample_on_cells(s, 0.0, 1.0, 10, x0, 0.0, r, v, pr);
  for (int i = 0; i < 10; ++i) EXPECT_DOUBLE_EQ(r[i], i < 5 ? 1.0 : 0.125);
  EXPECT_THROW(sample_on_cells(s, 0.0, 1.0, 10, x0, -1.0, r, v, pr), std::invalid_argument);
}

TEST(ExactRiemann, SlowlyMovingContact) {
  // Toro's numerical Test 5: left blast shifted by -19.59745, contact speed ~ 5e-5.
  const Star a = solve_star({1, 0, 1000}, kAir, {1, 0, 0.01}, kAir);
  const Star b = solve_star({1, -19.59745, 1000}, kAir, {1, -19.59745, 0.01}, kAir);
  EXPECT_NEAR(b.p, a.p, 1e-12 * a.p);
  EXPECT_NEAR(b.u, a.u - 19.59745, 1e-11);
  EXPECT_GT(b.u, 0.0);
  EXPECT_LT(b.u, 1e-4);
}

TEST(ExactRiemann, WaterAirStiffenedGas) {
  const Primitive water{1000, 0, 1e9}, air{50, 0, 1e5};
  const RiemannSolution s(water, kWater, air, kAir);
  EXPECT_FALSE(s.star().vacuum);
  EXPECT_NEAR(s.star().p, 1.41905e7, 1e-4 * 1.41905e7);
  EXPECT_NEAR(s.star().u, 482.61, 1e-4 * 482.61);
  // Rarefaction into the water, shock into the air.
  EXPECT_LT(s.left_head(), s.left_tail());
  EXPECT_EQ(s.right_tail(), s.right_head());
  EXPECT_NEAR(s.left_head(), -sound_speed(1000, 1e9, kWater), 1e-9);
  check_wave(s, -1, 1e-11);
  check_wave(s, +1, 1e-11);
  // Sides follow the material interface.
  EXPECT_EQ(s.sample(s.contact() - 1.0).side, -1);
  EXPECT_EQ(s.sample(s.contact() + 1.0).side, +1);
  EXPECT_NEAR(s.sample(s.contact() - 1.0).rho, s.star().rho_left, 0.0);
  EXPECT_NEAR(s.sample(s.contact() + 1.0).rho, s.star().rho_right, 0.0);
}

TEST(ExactRiemann, MixedMaterialsJumpConditions) {
  const Material helium{5.0 / 3.0, 0.0};
  struct Case {
    Primitive L;
    Material mL;
    Primitive R;
    Material mR;
  };
  const Case cases[] = {
      {{1, 0, 1}, kAir, {0.138, 0, 1}, helium},               // pure contact at rest
      {{1, 0.5, 10}, helium, {0.125, -1, 0.1}, kAir},         // two gammas, shock + shock
      {{1, -0.5, 1}, kAir, {0.5, 1.5, 0.3}, helium},          // two rarefactions
      {{50, 300, 1e5}, kAir, {1000, 0, 1e5}, kWater},         // air hitting water
      {{1000, 0, -1e8}, kWater, {1.2, 0, 1e5}, kAir},         // water in tension | air
      {{1000, 100, 1e5}, kWater, {1000, -100, 1e5}, kWater},  // water impact
      {{1000, -50, 1e5}, kWater, {1000, 50, 1e5}, kWater},    // water in tension (p* < 0)
  };
  for (std::size_t i = 0; i < std::size(cases); ++i) {
    SCOPED_TRACE(i);
    const Case& c = cases[i];
    const RiemannSolution s(c.L, c.mL, c.R, c.mR);
    EXPECT_FALSE(s.star().vacuum);
    check_wave(s, -1, 1e-11);
    check_wave(s, +1, 1e-11);
    EXPECT_LE(s.left_head(), s.left_tail());
    EXPECT_LE(s.left_tail(), s.contact());
    EXPECT_LE(s.contact(), s.right_tail());
    EXPECT_LE(s.right_tail(), s.right_head());
  }
  // Tension in water: the star pressure is negative but admissible.
  const Star t = solve_star({1000, -50, 1e5}, kWater, {1000, 50, 1e5}, kWater);
  EXPECT_LT(t.p, 0.0);
  EXPECT_GT(t.p + kWater.pinf, 0.0);
}

TEST(ExactRiemann, UniformStateIsPreserved) {
  const Primitive q{1.3, 0.7, 2.1};
  const RiemannSolution s(q, kAir, q, kAir);
  EXPECT_NEAR(s.star().p, q.p, 1e-14);
  EXPECT_NEAR(s.star().u, q.u, 1e-14);
  for (double xi : {-5.0, -1.0, 0.0, 0.7, 1.0, 5.0}) {
    const auto r = s.sample(xi);
    EXPECT_NEAR(r.rho, q.rho, 1e-13);
    EXPECT_NEAR(r.u, q.u, 1e-13);
    EXPECT_NEAR(r.p, q.p, 1e-13);
  }
}

TEST(ExactRiemann, MirrorSymmetry) {
  for (const auto& c : kToro) {
    SCOPED_TRACE(c.name);
    check_mirror(c.L, kAir, c.R, kAir);
  }
  check_mirror({1000, 0, 1e9}, kWater, {50, 0, 1e5}, kAir);
  check_mirror({50, 300, 1e5}, kAir, {1000, 0, 1e5}, kWater);
  check_mirror({1, 0.5, 10}, Material{5.0 / 3.0, 0.0}, {0.125, -1, 0.1}, kAir);
  check_mirror({1, -4, 0.4}, kAir, {1, 4, 0.4}, kAir);    // symmetric vacuum
  check_mirror({1, -3, 0.4}, kAir, {0.5, 5, 0.1}, kAir);  // asymmetric vacuum
}

TEST(ExactRiemann, VacuumGeneration) {
  const Primitive L{1, -4, 0.4}, R{1, 4, 0.4};
  const RiemannSolution s(L, kAir, R, kAir);
  const double c = std::sqrt(1.4 * 0.4);
  ASSERT_TRUE(s.star().vacuum);
  EXPECT_EQ(s.star().p, 0.0);
  EXPECT_NEAR(s.left_head(), L.u - c, 1e-14);
  EXPECT_NEAR(s.right_head(), R.u + c, 1e-14);
  EXPECT_NEAR(s.left_tail(), L.u + 2.0 * c / 0.4, 1e-14);  // vacuum fronts
  EXPECT_NEAR(s.right_tail(), R.u - 2.0 * c / 0.4, 1e-14);
  EXPECT_NEAR(s.contact(), 0.0, 1e-14);

  const auto mid = s.sample(0.0);
  EXPECT_EQ(mid.rho, 0.0);
  EXPECT_EQ(mid.p, 0.0);
  // Outside the fans: initial states.
  const auto outL = s.sample(s.left_head() - 1e-9);
  EXPECT_DOUBLE_EQ(outL.rho, 1.0);
  EXPECT_DOUBLE_EQ(outL.u, -4.0);
  const auto outR = s.sample(s.right_head() + 1e-9);
  EXPECT_DOUBLE_EQ(outR.rho, 1.0);
  EXPECT_DOUBLE_EQ(outR.u, 4.0);
  EXPECT_EQ(outR.side, 1);
  // Fans: continuous at the heads, density -> 0 at the vacuum fronts, monotone in between.
  EXPECT_NEAR(s.sample(s.left_head() + 1e-12).rho, 1.0, 1e-10);
  EXPECT_NEAR(s.sample(s.right_head() - 1e-12).rho, 1.0, 1e-10);
  EXPECT_LT(s.sample(s.left_tail() - 1e-6).rho, 1e-10);
  EXPECT_LT(s.sample(s.right_tail() + 1e-6).p, 1e-10);
  EXPECT_NEAR(s.sample(s.left_tail() - 1e-9).u, s.left_tail(), 1e-8);
  double prev = 2.0;
  for (int i = 1; i < 100; ++i) {
    const double xi = s.left_head() + (s.left_tail() - s.left_head()) * i / 100.0;
    const auto q = s.sample(xi);
    EXPECT_LT(q.rho, prev);
    prev = q.rho;
    // Isentrope and characteristic xi = u - c inside the left fan.
    EXPECT_NEAR(q.p / std::pow(q.rho, 1.4), 0.4, 1e-12);
    EXPECT_NEAR(q.u - sound_speed(q.rho, q.p, kAir), xi, 1e-12);
    EXPECT_EQ(q.side, -1);
  }
  // Vacuum region belongs to the nearer material.
  EXPECT_EQ(s.sample(-0.1).side, -1);
  EXPECT_EQ(s.sample(0.1).side, 1);

  // Just at the vacuum threshold 4 c / (gamma - 1) = u_R - u_L: vacuum; slightly below: not.
  const double du = 4.0 * c / 0.4;
  EXPECT_TRUE(solve_star({1, -0.5 * du - 1e-9, 0.4}, kAir, {1, 0.5 * du + 1e-9, 0.4}, kAir).vacuum);
  const Star nv = solve_star({1, -0.49 * du, 0.4}, kAir, {1, 0.49 * du, 0.4}, kAir);
  EXPECT_FALSE(nv.vacuum);
  EXPECT_GT(nv.p, 0.0);
  EXPECT_LT(nv.p, 1e-6);
}

TEST(ExactRiemann, InvalidInputThrows) {
  const Primitive ok{1, 0, 1};
  EXPECT_THROW(solve_star({0, 0, 1}, kAir, ok, kAir), std::runtime_error);
  EXPECT_THROW(solve_star(ok, kAir, {-1, 0, 1}, kAir), std::runtime_error);
  EXPECT_THROW(solve_star({1, 0, 0}, kAir, ok, kAir), std::runtime_error);
  EXPECT_THROW(solve_star(ok, kAir, {1, 0, -1}, kAir), std::runtime_error);
  EXPECT_THROW(solve_star({1000, 0, -6e8}, kWater, ok, kAir), std::runtime_error);
  EXPECT_THROW(solve_star(ok, Material{1.0, 0.0}, ok, kAir), std::runtime_error);
  EXPECT_THROW(solve_star(ok, kAir, ok, Material{1.4, -1.0}), std::runtime_error);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(solve_star({1, nan, 1}, kAir, ok, kAir), std::runtime_error);
  EXPECT_THROW(RiemannSolution(ok, kAir, {1, 0, 0}, kAir), std::runtime_error);
  // Cavitation of a stiffened gas is not supported.
  EXPECT_THROW(solve_star({1000, -5000, 1e5}, kWater, {1000, 5000, 1e5}, kWater), std::runtime_error);
  // Water in tension is fine as long as p + pinf > 0 (and the air does not cavitate).
  EXPECT_NO_THROW(solve_star({1000, 0, -5e8}, kWater, {1.2, 0, 1e5}, kAir));
  EXPECT_THROW(solve_star({1000, 0, -5e8}, kWater, {1, 0, 1}, kAir), std::runtime_error);
}

}  // namespace
