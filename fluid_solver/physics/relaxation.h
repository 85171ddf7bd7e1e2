// Per-cell relaxation and exchange operators of the two-phase model, applied to the conservative
// state of one cell (docs/methods.md §2.5 and §6). All of them conserve mixture mass, momentum and energy.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include "common/eos/stiffened_gas.h"
#include "fluid_solver/core/scene.h"

namespace cosim::fluid {

// Conservative two-phase state of one cell (3 velocity slots; unused ones stay zero).
struct CellState2 {
  double alpha0;
  double m[2];
  double mom[2][3];
  double E[2];
};

// Instantaneous pressure relaxation with implicit interface pressure p_I = p (docs/methods.md §2.5(b)) on
// one cell, given phase masses m, kinetic energies per unit mass ke, total energies E and alpha0:
// each phase follows e_k - e_k0 = -p (v_k - v_k0); for stiffened gases sum_k m_k v_k(p) = 1 is a
// quadratic in p, solved in closed form and polished with one Newton step. Branch-free so that the
// solver's row loops over it vectorise (the instantaneous velocity relaxation, docs/methods.md §2.5(a),
// lives in those loops too). A state whose equilibrium pressure is not admissible is left
// unchanged (the admissibility check then reports it). Returns the pressure.
[[gnu::always_inline]] inline double relax_pressure_kernel(double& alpha0, const double m0, const double m1,
                                                           const double ke0, const double ke1, double& E0, double& E1,
                                                           const eos::StiffenedGas& e0, const eos::StiffenedGas& e1) {
  const double g0 = e0.gamma, g1 = e1.gamma, pi0 = e0.pinf, pi1 = e1.pinf;
  const double A0 = m0 * (g0 - 1.0) / g0, A1 = m1 * (g1 - 1.0) / g1;
  const double a0 = E0 / m0 - ke0 - e0.q, a1 = E1 / m1 - ke1 - e1.q;  // e_k0 - q_k
  const double b0 = alpha0 / m0, b1 = (1.0 - alpha0) / m1;            // v_k0
  // (1 - A0 b0 - A1 b1) p^2 + B p + C = 0 from sum_k m_k v_k(p) = 1 with
  // v_k(p) = (g_k - 1)(e_k0 - q_k + p v_k0) / (g_k (p + pinf_k)).
  const double qa = 1.0 - A0 * b0 - A1 * b1;
  const double qb = pi0 + pi1 - A0 * (a0 + b0 * pi1) - A1 * (a1 + b1 * pi0);
  const double qc = pi0 * pi1 - A0 * a0 * pi1 - A1 * a1 * pi0;
  const double sq = std::sqrt(std::max(qb * qb - 4.0 * qa * qc, 0.0));
  // Larger root, written without cancellation for either sign of qb.
  double p = qb > 0.0 ? 2.0 * qc / (-qb - sq) : (-qb + sq) / (2.0 * qa);
  // One Newton step on f(p) = sum_k m_k v_k(p) - 1 removes the round-off of the closed form.
  const double d0 = 1.0 / (p + pi0), d1 = 1.0 / (p + pi1);
  const double f = A0 * (a0 + p * b0) * d0 + A1 * (a1 + p * b1) * d1 - 1.0;
  const double df = A0 * (b0 * pi0 - a0) * d0 * d0 + A1 * (b1 * pi1 - a1) * d1 * d1;
  const double step = f / df;
  p -= (df < 0.0 && step == step) ? step : 0.0;
  const bool ok = p > -std::min(pi0, pi1) && p < 1e300;
  const double v0 = (g0 - 1.0) * (a0 + p * b0) / (g0 * (p + pi0));
  const double v1 = (g1 - 1.0) * (a1 + p * b1) / (g1 * (p + pi1));
  const double al0 = m0 * v0, al1 = m1 * v1;
  const double nE0 = m0 * (a0 + e0.q - p * (v0 - b0) + ke0);
  const double nE1 = m1 * (a1 + e1.q - p * (v1 - b1) + ke1);
  E0 = ok ? nE0 : E0;
  E1 = ok ? nE1 : E1;
  alpha0 = ok ? al0 / (al0 + al1) : alpha0;
  return p;
}

// Drag over dt with the coefficient frozen at its start value: the slip decays exactly as
// exp(-dt beta (1/m_g + 1/m_p)). Phase 0 is the gas, phase 1 the particles. The particles' kinetic
// energy change is taken from the gas energy, so the dissipation heats the gas (docs/methods.md §6.1).
// Returns the drag coefficient beta [kg/(m^3 s)] it used (0 without slip).
double apply_drag(CellState2& s, const eos::StiffenedGas (&eos)[2], const Exchange& ex, int dim, double dt);

// Heat exchange (Ranz-Marshall) over dt at frozen densities and coefficient: T_g - T_p decays
// exponentially; the heat leaves the gas and enters the particles.
void apply_heat_transfer(CellState2& s, const eos::StiffenedGas (&eos)[2], const Exchange& ex, int dim, double dt);

}  // namespace cosim::fluid
