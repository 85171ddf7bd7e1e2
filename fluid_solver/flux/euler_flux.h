// Physical Euler quantities of a stiffened-gas phase state along grid direction D.
#pragma once

#include "common/eos/stiffened_gas.h"
#include "fluid_solver/core/layout.h"

namespace cosim::fluid {

template <int DIM>
inline double kinetic(const PhaseState<DIM>& s) {
  double k = 0;
  for (int d = 0; d < DIM; ++d) k += s.u[d] * s.u[d];
  return 0.5 * s.rho * k;
}

// Total energy per unit volume rho E.
template <int DIM>
inline double total_energy(const PhaseState<DIM>& s, const eos::StiffenedGas& e) {
  return e.rho_e(s.rho, s.p) + kinetic(s);
}

// F_D(U) = (rho u_D, rho u u_D + p e_D, (rho E + p) u_D).
template <int DIM, int D>
inline PhaseFlux<DIM> physical_flux(const PhaseState<DIM>& s, double rhoE) {
  PhaseFlux<DIM> f;
  const double un = s.u[D];
  f.mass = s.rho * un;
  for (int d = 0; d < DIM; ++d) f.mom[d] = s.rho * s.u[d] * un;
  f.mom[D] += s.p;
  f.energy = (rhoE + s.p) * un;
  return f;
}

}  // namespace cosim::fluid
