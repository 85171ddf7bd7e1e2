// Same-phase contact flux of a phase that is only a trace on both sides of a face (volume fraction below
// `exchange.trace_alpha`, docs/methods.md §2.7). Its pressure is the carrier's (instantaneous pressure
// relaxation), so its own acoustic waves carry nothing and are not resolved: the state is advected upwind with
// the face velocity u_f = (u_n- + u_n+)/2 and the pressure acts centrally,
//   F = rho_up (1, u_up, E_up) u_f + p_f (0, e_D, u_f),   p_f = (p- + p+)/2.
// It is stable for |u_f| dt / dx <= 1, the carrier's step, however fast the phase's sound speed.
#pragma once

#include "fluid_solver/flux/euler_flux.h"

namespace cosim::fluid {

template <int DIM, int D>
inline PhaseFlux<DIM> trace_flux(const PhaseState<DIM>& L, const PhaseState<DIM>& R, const eos::StiffenedGas& e) {
  const double uf = 0.5 * (L.u[D] + R.u[D]), pf = 0.5 * (L.p + R.p);
  const PhaseState<DIM>& up = uf > 0.0 ? L : R;
  PhaseFlux<DIM> f;
  f.mass = up.rho * uf;
  for (int d = 0; d < DIM; ++d) f.mom[d] = f.mass * up.u[d];
  f.mom[D] += pf;
  f.energy = total_energy(up, e) * uf + pf * uf;
  return f;
}

}  // namespace cosim::fluid
