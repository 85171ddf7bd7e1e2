// AUFS: artificially upstream flux-vector splitting (Sun & Takayama, JCP 189 (2003)),
// docs/methods.md §1.2, with the stiffened-gas dissipation vector D_SG of docs/methods.md §1.3.
// For two states of the same phase (same EOS), face normal e_D.
#pragma once

#include <algorithm>

#include "fluid_solver/flux/euler_flux.h"

namespace cosim::fluid {

template <int DIM, int D>
inline PhaseFlux<DIM> aufs_flux(const PhaseState<DIM>& L, const PhaseState<DIM>& R, const eos::StiffenedGas& e) {
  const double g1 = e.gamma - 1.0;
  const double unL = L.u[D], unR = R.u[D];
  const double cbar = 0.5 * (L.c + R.c);
  const double s1 = 0.5 * (unL + unR);
  // Two-rarefaction estimates of the intermediate state (docs/methods.md §1.2 step 3).
  const double ustar = s1 + (L.c - R.c) / g1;
  const double cstar = cbar + 0.25 * g1 * (unL - unR);
  const bool left_up = s1 > 0.0;
  const double s2 = left_up ? std::min({0.0, unL - L.c, ustar - cstar}) : std::max({0.0, ustar + cstar, unR + R.c});
  const double den = s1 - s2;
  const double M = den != 0.0 ? s1 / den : 0.0;

  // Pressure part with Steger-Warming dissipation at the common sound speed (step 5).
  const double inv_c = 1.0 / cbar;
  const double dL = (L.p + e.gamma * e.pinf) * inv_c, dR = (R.p + e.gamma * e.pinf) * inv_c;
  const double h0 = cbar * cbar / g1;
  double kL = 0, kR = 0;
  for (int d = 0; d < DIM; ++d) {
    kL += L.u[d] * L.u[d];
    kR += R.u[d] * R.u[d];
  }
  PhaseFlux<DIM> f1;
  f1.mass = 0.5 * (dL - dR);
  for (int d = 0; d < DIM; ++d) f1.mom[d] = 0.5 * (dL * L.u[d] - dR * R.u[d]);
  f1.mom[D] += 0.5 * (L.p + R.p);
  f1.energy = 0.5 * (L.p * unL + R.p * unR) + 0.5 * (dL * (h0 + 0.5 * kL) - dR * (h0 + 0.5 * kR));

  // Upwind part from the upstream state (step 6): (u_n - s2) U + P.
  const PhaseState<DIM>& U = left_up ? L : R;
  const double un = U.u[D];
  const double w = un - s2;
  const double rhoE = e.rho_e(U.rho, U.p) + 0.5 * U.rho * (left_up ? kL : kR);
  PhaseFlux<DIM> f;
  f.mass = (1.0 - M) * f1.mass + M * (w * U.rho);
  for (int d = 0; d < DIM; ++d) f.mom[d] = (1.0 - M) * f1.mom[d] + M * (w * U.rho * U.u[d]);
  f.mom[D] += M * U.p;
  f.energy = (1.0 - M) * f1.energy + M * (w * rhoE + U.p * un);
  return f;
}

}  // namespace cosim::fluid
