// Rusanov (local Lax-Friedrichs) flux: F = (F_L + F_R)/2 - smax (U_R - U_L)/2.
#pragma once

#include <algorithm>
#include <cmath>

#include "fluid_solver/flux/euler_flux.h"

namespace cosim::fluid {

template <int DIM, int D>
inline PhaseFlux<DIM> rusanov_flux(const PhaseState<DIM>& L, const PhaseState<DIM>& R, const eos::StiffenedGas& e) {
  const double EL = total_energy(L, e), ER = total_energy(R, e);
  const PhaseFlux<DIM> fL = physical_flux<DIM, D>(L, EL), fR = physical_flux<DIM, D>(R, ER);
  const double smax = std::max(std::abs(L.u[D]) + L.c, std::abs(R.u[D]) + R.c);
  PhaseFlux<DIM> f;
  f.mass = 0.5 * (fL.mass + fR.mass) - 0.5 * smax * (R.rho - L.rho);
  for (int d = 0; d < DIM; ++d)
    f.mom[d] = 0.5 * (fL.mom[d] + fR.mom[d]) - 0.5 * smax * (R.rho * R.u[d] - L.rho * L.u[d]);
  f.energy = 0.5 * (fL.energy + fR.energy) - 0.5 * smax * (ER - EL);
  return f;
}

}  // namespace cosim::fluid
