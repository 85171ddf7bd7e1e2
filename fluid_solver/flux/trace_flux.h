// Same-phase contact flux of a phase that is only a trace on both sides of a face (volume fraction below
// `exchange.trace_alpha`, docs/methods.md §2.7), and of a dispersed particle phase everywhere (§2.8). Its pressure
// is the carrier's (instantaneous pressure relaxation), so its own acoustic waves carry nothing and are not
// resolved: the state is carried upwind with the mean face velocity u_f = (u_n- + u_n+)/2 and, where the two sides
// approach each other, by their relative speed s = max(0, (u_n- - u_n+)/2) as in the kinetic splitting of
// pressureless gas dynamics (Bouchut, Jin and Li 2003) seen from the face; the pressure acts centrally:
//   F = U_up u_f + s (U- - U+) + (0, p_f e_D, (p- u_n- + p+ u_n+)/2),   U = rho (1, u, E),   p_f = (p- + p+)/2.
// Stable for (|u_f| + s) dt / dx <= 1, within the carrier's step however fast the phase's sound speed. At a
// mirrored wall moving with v it carries the mass rho v of the moving wall and reflects the normal momentum of
// what arrives, 2 rho max(u_n - v, 0)^2.
#pragma once

#include <algorithm>

#include "fluid_solver/flux/euler_flux.h"

namespace cosim::fluid {

template <int DIM, int D>
inline PhaseFlux<DIM> trace_flux(const PhaseState<DIM>& L, const PhaseState<DIM>& R, const eos::StiffenedGas& e) {
  const double uf = 0.5 * (L.u[D] + R.u[D]), s = std::max(0.0, 0.5 * (L.u[D] - R.u[D]));
  const double pf = 0.5 * (L.p + R.p);
  const PhaseState<DIM>& up = uf > 0.0 ? L : R;
  const double EL = total_energy(L, e), ER = total_energy(R, e);
  PhaseFlux<DIM> f;
  f.mass = up.rho * uf + s * (L.rho - R.rho);
  for (int d = 0; d < DIM; ++d) f.mom[d] = up.rho * up.u[d] * uf + s * (L.rho * L.u[d] - R.rho * R.u[d]);
  f.mom[D] += pf;
  f.energy = (uf > 0.0 ? EL : ER) * uf + s * (EL - ER) + 0.5 * (L.p * L.u[D] + R.p * R.u[D]);
  return f;
}

// The same flux over a row of faces, branch-free so that the loop vectorises; the views are those of aufs_row
// (left[v][f], v = rho, u_0..u_{DIM-1}, p, c). GRAN: a phase with a granular temperature (docs/methods.md §2.9),
// whose granular energy per unit mass kl / kr is carried in its energy, and whose material energy rho e is carried
// the same way into fh (so that E - e - u^2/2 keeps what the flux takes from the mean motion).
template <int DIM, int D, bool GRAN = false>
inline void trace_row(int n, const double* const* left, const double* const* right, double* const* flux,
                      const eos::StiffenedGas& e, const double* kl = nullptr, const double* kr = nullptr,
                      double* fh = nullptr) {
  const double ig1 = 1.0 / (e.gamma - 1.0), gpinf = e.gamma * e.pinf, q = e.q;
#pragma GCC ivdep
  for (int f = 0; f < n; ++f) {
    const double rL = left[0][f], rR = right[0][f], pL = left[1 + DIM][f], pR = right[1 + DIM][f];
    const double unL = left[1 + D][f], unR = right[1 + D][f];
    const double uf = 0.5 * (unL + unR), s = std::max(0.0, 0.5 * (unL - unR));
    const double wl = uf > 0.0 ? 1.0 : 0.0, wr = 1.0 - wl;
    double kL = 0, kR = 0;
    for (int d = 0; d < DIM; ++d) {
      kL += left[1 + d][f] * left[1 + d][f];
      kR += right[1 + d][f] * right[1 + d][f];
    }
    const double eL = (pL + gpinf) * ig1 + rL * q, eR = (pR + gpinf) * ig1 + rR * q;
    double EL = eL + 0.5 * rL * kL, ER = eR + 0.5 * rR * kR;
    const double a = wl * uf + s, b = wr * uf - s;  // F = U- a + U+ b + pressure terms
    if constexpr (GRAN) {
      EL += rL * kl[f];
      ER += rR * kr[f];
      fh[f] = eL * a + eR * b;
    }
    flux[0][f] = rL * a + rR * b;
    for (int d = 0; d < DIM; ++d) flux[1 + d][f] = rL * left[1 + d][f] * a + rR * right[1 + d][f] * b;
    flux[1 + D][f] += 0.5 * (pL + pR);
    flux[1 + DIM][f] = EL * a + ER * b + 0.5 * (pL * unL + pR * unR);
  }
}

}  // namespace cosim::fluid
