// AUFS over a whole row of faces, written without branches so that the loop vectorises
// (same formulas as aufs.h, docs/methods.md §1.2-1.3). Used for single-phase scenes, where the face
// loop is the hot spot. Inputs are structure-of-arrays views: for face f, left/right primitive
// variable v is left[v][f] / right[v][f] with v = rho, u_0..u_{DIM-1}, p, c.
#pragma once

#include <algorithm>

#include "common/eos/stiffened_gas.h"

namespace cosim::fluid {

template <int DIM, int D, bool LOW_MACH>
inline void aufs_row(int n, const double* const* left, const double* const* right, double* const* flux,
                     const eos::StiffenedGas& e, double low_mach_cutoff) {
  const double g = e.gamma, g1 = e.gamma - 1.0, ig1 = 1.0 / g1, gpinf = e.gamma * e.pinf, q = e.q;
  const double* rL = left[0];
  const double* rR = right[0];
  const double* pL = left[1 + DIM];
  const double* pR = right[1 + DIM];
  const double* cL = left[2 + DIM];
  const double* cR = right[2 + DIM];
  const double* uLp[DIM];
  const double* uRp[DIM];
  double* fm_out[DIM];
  for (int d = 0; d < DIM; ++d) {
    uLp[d] = left[1 + d];
    uRp[d] = right[1 + d];
    fm_out[d] = flux[1 + d];
  }
  double* f_mass = flux[0];
  double* f_energy = flux[1 + DIM];
#pragma GCC ivdep
  for (int f = 0; f < n; ++f) {
    double uL[DIM], uR[DIM];
    for (int d = 0; d < DIM; ++d) {
      uL[d] = uLp[d][f];
      uR[d] = uRp[d][f];
    }
    if constexpr (LOW_MACH) {  // paper eqs. 10-11
      double qL = 0, qR = 0;
      for (int d = 0; d < DIM; ++d) {
        qL += uL[d] * uL[d];
        qR += uR[d] * uR[d];
      }
      const double M = std::max(std::sqrt(qL) / cL[f], std::sqrt(qR) / cR[f]);
      const double z = std::min(1.0, std::max(M, low_mach_cutoff));
      for (int d = 0; d < DIM; ++d) {
        const double mean = 0.5 * (uL[d] + uR[d]), hj = 0.5 * (uL[d] - uR[d]);
        uL[d] = mean + z * hj;
        uR[d] = mean - z * hj;
      }
    }
    const double unL = uL[D], unR = uR[D];
    const double cbar = 0.5 * (cL[f] + cR[f]);
    const double s1 = 0.5 * (unL + unR);
    const double ustar = s1 + (cL[f] - cR[f]) * ig1;
    const double cstar = cbar + 0.25 * g1 * (unL - unR);
    const bool left_up = s1 > 0.0;
    const double s2l = std::min(0.0, std::min(unL - cL[f], ustar - cstar));
    const double s2r = std::max(0.0, std::max(ustar + cstar, unR + cR[f]));
    const double s2 = left_up ? s2l : s2r;
    const double den = s1 - s2;
    const double M = s1 / (den + (den == 0.0 ? 1.0 : 0.0));  // s1 = s2 = 0 gives M = 0
    double kL = 0, kR = 0;
    for (int d = 0; d < DIM; ++d) {
      kL += uL[d] * uL[d];
      kR += uR[d] * uR[d];
    }
    const double inv_c = 1.0 / cbar;
    const double dL = (pL[f] + gpinf) * inv_c, dR = (pR[f] + gpinf) * inv_c;
    const double h0 = cbar * cbar * ig1;
    // Upwind state (selected variable by variable; the density is blended arithmetically so that
    // both loads happen unconditionally and the loop stays free of branches).
    const double wl = left_up ? 1.0 : 0.0;
    const double ru = wl * rL[f] + (1.0 - wl) * rR[f];
    const double pu = left_up ? pL[f] : pR[f];
    const double ku = left_up ? kL : kR;
    const double unu = left_up ? unL : unR;
    const double w = unu - s2;
    const double Eu = (pu + gpinf) * ig1 + ru * q + 0.5 * ru * ku;
    const double a = 1.0 - M;
    f_mass[f] = a * 0.5 * (dL - dR) + M * (w * ru);
    for (int d = 0; d < DIM; ++d) {
      const double uu = left_up ? uL[d] : uR[d];
      double fm = a * 0.5 * (dL * uL[d] - dR * uR[d]) + M * (w * ru * uu);
      if (d == D) fm += a * 0.5 * (pL[f] + pR[f]) + M * pu;
      fm_out[d][f] = fm;
    }
    f_energy[f] = a * (0.5 * (pL[f] * unL + pR[f] * unR) + 0.5 * (dL * (h0 + 0.5 * kL) - dR * (h0 + 0.5 * kR))) +
                  M * (w * Eu + pu * unu);
  }
  (void)g;
}

}  // namespace cosim::fluid
