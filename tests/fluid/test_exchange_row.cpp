// The vectorised exchange row (physics/exchange_row.h) against the cell operators it reproduces: apply_drag,
// apply_heat_transfer and GranularGas::after_collisions on each cell, bit for bit, over rows of gas-particle
// states that visit every branch: no slip, no temperature difference, the dilute, blended and dense drag regimes,
// granular energies above, at and below zero, volume fractions below the granular floor.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "common/eos/materials.h"
#include "fluid_solver/physics/exchange_row.h"
#include "fluid_solver/physics/relaxation.h"

namespace cosim::fluid::test {
namespace {

struct Row {
  std::vector<double> alpha, m[2], mom[2][3], E[2], heat;
};

template <int DIM>
Row random_row(int n, const eos::StiffenedGas (&e)[2], unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  Row r;
  r.alpha.resize(n);
  r.heat.resize(n);
  for (int k = 0; k < 2; ++k) {
    r.m[k].resize(n);
    r.E[k].resize(n);
    for (int d = 0; d < 3; ++d) r.mom[k][d].assign(n, 0.0);
  }
  const double alphas_p[] = {1e-6, 3e-6, 2e-5, 0.01, 0.05, 0.08, 0.2, 0.45, 0.5};
  for (int i = 0; i < n; ++i) {
    const double ap = alphas_p[i % 9] * (1.0 + 0.1 * U(gen));
    r.alpha[i] = 1.0 - ap;
    const double rho_g = 1.0 + 20.0 * U(gen), rho_p = 19000.0 + 300.0 * U(gen);
    const double Tg = 300.0 + 2500.0 * U(gen), Tp = i % 7 == 0 ? Tg : 300.0 + 2500.0 * U(gen);
    const double mg = r.alpha[i] * rho_g, mp = ap * rho_p;
    r.m[0][i] = mg;
    r.m[1][i] = mp;
    double k0 = 0, k1 = 0;
    for (int d = 0; d < DIM; ++d) {
      const double ug = 800.0 * (U(gen) - 0.5), up = i % 5 == 0 ? ug : 800.0 * (U(gen) - 0.5);
      r.mom[0][d][i] = mg * ug;
      r.mom[1][d][i] = mp * up;
      k0 += 0.5 * mg * ug * ug;
      k1 += 0.5 * mp * up * up;
    }
    // Material energies at the temperatures (e = cv T + q + pinf / rho + the datum's cold part).
    const auto rho_e = [&](const eos::StiffenedGas& s, double rho, double T) {
      const double cold = s.a0 == 0.0 ? 0.0 : s.a0 * std::pow(rho, s.gamma - 1.0) / (s.gamma - 1.0);
      return rho * (s.cv * T + s.q + s.pinf / rho + cold);
    };
    const double h = ap * rho_e(e[1], rho_p, Tp);
    const double G = i % 4 == 0 ? 0.0 : (i % 4 == 1 ? -1e-9 * mp : mp * 2e3 * U(gen));  // granular energy
    r.E[0][i] = r.alpha[i] * rho_e(e[0], rho_g, Tg) + k0;
    r.E[1][i] = h + k1 + G;
    r.heat[i] = h;
  }
  return r;
}

template <int DIM>
TwoPhaseRow<DIM> views(Row& r) {
  TwoPhaseRow<DIM> v;
  v.alpha = r.alpha.data();
  for (int k = 0; k < 2; ++k) {
    v.m[k] = r.m[k].data();
    for (int d = 0; d < DIM; ++d) v.mom[k][d] = r.mom[k][d].data();
    v.E[k] = r.E[k].data();
  }
  v.heat = r.heat.data();
  return v;
}

// The cell-by-cell loop the solver ran before the row kernel (its exchange step).
template <int DIM>
void reference(Row& r, const eos::StiffenedGas (&e)[2], const Exchange& ex, double dt, bool drag, bool heat,
               bool gran) {
  for (std::size_t c = 0; c < r.alpha.size(); ++c) {
    const auto kinetic1 = [&] {
      double q = 0;
      for (int d = 0; d < DIM; ++d) q += r.mom[1][d][c] * r.mom[1][d][c];
      return 0.5 * q / r.m[1][c];
    };
    const double G = gran ? r.E[1][c] - kinetic1() - r.heat[c] : 0.0;
    CellState2 s{};
    s.alpha0 = r.alpha[c];
    for (int k = 0; k < 2; ++k) {
      s.m[k] = r.m[k][c];
      for (int d = 0; d < DIM; ++d) s.mom[k][d] = r.mom[k][d][c];
      s.E[k] = r.E[k][c];
    }
    s.E[1] -= G;
    const double beta = drag ? apply_drag(s, e, ex, DIM, dt) : 0.0;
    if (heat) apply_heat_transfer(s, e, ex, DIM, dt);
    s.E[1] += G;
    for (int k = 0; k < 2; ++k) {
      for (int d = 0; d < DIM; ++d) r.mom[k][d][c] = s.mom[k][d];
      r.E[k][c] = s.E[k];
    }
    if (gran) {
      const double m = s.m[1];
      const double k = ex.granular.after_collisions(1.0 - s.alpha0, G / m * std::exp(-2.0 * dt * beta / m), dt);
      r.heat[c] = s.E[1] - kinetic1() - m * k;
    }
  }
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

template <int DIM, bool DRAG, bool HEAT, bool GRAN>
void check_row(unsigned seed) {
  const eos::Material* w = eos::find_material("tungsten");
  eos::StiffenedGas e[2] = {
      eos::find_material("air")->sg,
      eos::with_reference_temperature(w->sg, w->reference_density, w->reference_pressure, w->reference_temperature)};
  ASSERT_GT(e[1].a0, 0.0);  // the temperature datum's power is taken apart: test it
  Exchange ex;
  ex.drag_law = DragLaw::AkhatovVainshtein;
  ex.particle_diameter = 1e-4;
  const int n = 61;  // not a multiple of the vector width: the loops' tails run too
  Row a = random_row<DIM>(n, e, seed), b = a;
  const double dt = 4e-7;
  reference<DIM>(a, e, ex, dt, DRAG, HEAT, GRAN);
  std::vector<double> scratch(static_cast<std::size_t>(kExchangeScratch) * n, std::nan(""));
  exchange_row<DIM, DRAG, HEAT, GRAN>(n, views<DIM>(b), e, ex, dt, scratch.data());
  SCOPED_TRACE(testing::Message() << "DIM " << DIM << " drag " << DRAG << " heat " << HEAT << " granular " << GRAN);
  EXPECT_TRUE(same_bits(a.alpha, b.alpha));
  for (int k = 0; k < 2; ++k) {
    EXPECT_TRUE(same_bits(a.m[k], b.m[k]));
    EXPECT_TRUE(same_bits(a.E[k], b.E[k])) << "energy of phase " << k;
    for (int d = 0; d < DIM; ++d) EXPECT_TRUE(same_bits(a.mom[k][d], b.mom[k][d])) << "momentum " << k << d;
  }
  if (GRAN) { EXPECT_TRUE(same_bits(a.heat, b.heat)); }
  // The row changed the states (the comparison is not between two untouched rows).
  const Row orig = random_row<DIM>(n, e, seed);
  EXPECT_FALSE(same_bits(orig.E[1], b.E[1]) && same_bits(orig.heat, b.heat));
}

TEST(ExchangeRow, MatchesTheCellOperatorsBitForBit) {
  check_row<3, true, true, true>(1);
  check_row<3, true, true, false>(2);
  check_row<3, true, false, true>(3);
  check_row<3, false, true, true>(4);
  check_row<3, false, false, true>(5);
  check_row<2, true, true, true>(6);
  check_row<2, true, false, false>(7);
  check_row<1, true, true, true>(8);
  check_row<1, false, true, false>(9);
}

}  // namespace
}  // namespace cosim::fluid::test
