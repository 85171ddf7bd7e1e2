// HLLC approximate Riemann solver (Toro ch. 10) with Davis wave-speed bounds, valid for two
// different stiffened-gas materials on the two sides (docs/methods.md §2.3(b)). Also returns the
// contact speed u* and pressure p* that the DEM Lagrangian fluxes need.
#pragma once

#include <algorithm>

#include "fluid_solver/flux/euler_flux.h"

namespace cosim::fluid {

template <int DIM>
struct HllcResult {
  PhaseFlux<DIM> flux;
  double ustar;
  double pstar;
};

template <int DIM, int D>
inline HllcResult<DIM> hllc_flux(const PhaseState<DIM>& L, const eos::StiffenedGas& eL, const PhaseState<DIM>& R,
                                 const eos::StiffenedGas& eR) {
  const double unL = L.u[D], unR = R.u[D];
  const double SL = std::min(unL - L.c, unR - R.c);
  const double SR = std::max(unL + L.c, unR + R.c);
  const double mL = L.rho * (SL - unL), mR = R.rho * (SR - unR);
  const double SM = (R.p - L.p + mL * unL - mR * unR) / (mL - mR);
  const double pstar = L.p + mL * (SM - unL);
  HllcResult<DIM> r;
  r.ustar = SM;
  r.pstar = pstar;
  const bool left = SM > 0.0;
  const PhaseState<DIM>& K = left ? L : R;
  const eos::StiffenedGas& eK = left ? eL : eR;
  const double S = left ? SL : SR;
  const double rhoE = total_energy(K, eK);
  PhaseFlux<DIM> f = physical_flux<DIM, D>(K, rhoE);
  if ((left && SL >= 0.0) || (!left && SR <= 0.0)) {
    r.flux = f;
    return r;
  }
  // F* = F_K + S_K (U*_K - U_K), Toro eq. 10.38-10.39.
  const double unK = K.u[D];
  const double fac = (S - unK) / (S - SM);
  const double rho_s = K.rho * fac;
  f.mass += S * (rho_s - K.rho);
  for (int d = 0; d < DIM; ++d) {
    const double us = d == D ? SM : K.u[d];
    f.mom[d] += S * (rho_s * us - K.rho * K.u[d]);
  }
  const double E_s = rho_s * (rhoE / K.rho + (SM - unK) * (SM + K.p / (K.rho * (S - unK))));
  f.energy += S * (E_s - rhoE);
  r.flux = f;
  return r;
}

}  // namespace cosim::fluid
