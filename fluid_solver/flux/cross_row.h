// The DEM cross contacts of two phases over a row of faces (docs/methods.md §2.3(b)-(c), §2.6 step 3), written
// without branches so that the loop vectorises; the same formulas, in the same order, as hllc_flux + cross_pair
// (flux/hllc.h, core/dem_face.h), so that a row gives bit for bit what the face-by-face loop gives.
//
// At face f the left state is (phase 0, phase 1) with phase-0 volume fraction aL, the right one likewise with aR.
// Only one pair has a contact fraction: phase p on the left against phase q = 1 - p on the right, p = 0 where
// aL > aR, S = |aL - aR|. Its two-material HLLC problem (Toro 10.38-10.39, Davis bounds) gives u*, p* and the
// flux at x/t = 0, which goes to the phase found there (p if u* > 0); the contact entering the cell downwind of
// u* brings phase 0 the Lagrangian terms S [X_0] (-u*, p*, p* u*), [X_0] = -1 for p = 0 and +1 for p = 1.
// Views: L0[v][f], L1[v][f], R0[v][f], R1[v][f] with v = rho, u_0..u_{DIM-1}, p, c.
#pragma once

#include <algorithm>

#include "common/eos/stiffened_gas.h"

namespace cosim::fluid {

// Output of cross_row: per phase the flux arrays (mass, mom[DIM], energy) to add to; the Lagrangian parts of
// phase 0 (alpha, normal momentum, energy) into the left and right cells, assigned (INTRA: added to `lag_right`
// only, the contact lying inside the cell); heat, where not null, gets the dispersed phase 1's material energy
// carried by its share of the flux.
struct CrossRowOut {
  double* const* flux0 = nullptr;
  double* const* flux1 = nullptr;
  double* const* lag_left = nullptr;
  double* const* lag_right = nullptr;
  double* heat = nullptr;
};

template <int DIM, int D, bool INTRA>
inline void cross_row(int n, const double* const* L0, const double* const* L1, const double* const* R0,
                      const double* const* R1, const double* aL, const double* aR, const eos::StiffenedGas (&e)[2],
                      const CrossRowOut& out) {
  constexpr int NV = 3 + DIM, P = 1 + DIM, C = 2 + DIM;  // variables per phase; pressure and sound-speed slots
  const double g0 = e[0].gamma, g1 = e[1].gamma, pi0 = e[0].pinf, pi1 = e[1].pinf, q0 = e[0].q, q1 = e[1].q;
  // Local copies of the views, so that the compiler sees them loop-invariant and the loop vectorises.
  const double *l0[NV], *l1[NV], *r0[NV], *r1[NV];
  for (int v = 0; v < NV; ++v) {
    l0[v] = L0[v];
    l1[v] = L1[v];
    r0[v] = R0[v];
    r1[v] = R1[v];
  }
  double *F0[2 + DIM] = {}, *F1[2 + DIM] = {};
  for (int v = 0; v < 2 + DIM && !INTRA; ++v) {
    F0[v] = out.flux0[v];
    F1[v] = out.flux1[v];
  }
  double* const la_l = INTRA ? nullptr : out.lag_left[0];
  double* const lm_l = INTRA ? nullptr : out.lag_left[1];
  double* const le_l = INTRA ? nullptr : out.lag_left[2];
  double* const la_r = out.lag_right[0];
  double* const lm_r = out.lag_right[1];
  double* const le_r = out.lag_right[2];
  double* const heat = out.heat;
#pragma GCC ivdep
  for (int f = 0; f < n; ++f) {
    const bool p0 = aL[f] > aR[f];  // phase 0 on the left, 1 on the right; otherwise the reverse
    const double S = p0 ? aL[f] - aR[f] : std::max(0.0, aR[f] - aL[f]);
    // The pair's states: "l" the left phase p, "r" the right phase q.
    const double rl = p0 ? l0[0][f] : l1[0][f], rr = p0 ? r1[0][f] : r0[0][f];
    const double pl = p0 ? l0[P][f] : l1[P][f], pr = p0 ? r1[P][f] : r0[P][f];
    const double cl = p0 ? l0[C][f] : l1[C][f], cr = p0 ? r1[C][f] : r0[C][f];
    double ul[DIM], ur[DIM];
    for (int d = 0; d < DIM; ++d) {
      ul[d] = p0 ? l0[1 + d][f] : l1[1 + d][f];
      ur[d] = p0 ? r1[1 + d][f] : r0[1 + d][f];
    }
    const double unL = ul[D], unR = ur[D];
    const double SL = std::min(unL - cl, unR - cr);
    const double SR = std::max(unL + cl, unR + cr);
    const double mL = rl * (SL - unL), mR = rr * (SR - unR);
    const double SM = (pr - pl + mL * unL - mR * unR) / (mL - mR);
    const double pstar = pl + mL * (SM - unL);
    // The state K found at x/t = 0 before the star correction: the left one where u* > 0.
    const bool left = SM > 0.0;
    const bool k0 = left == p0;  // K is phase 0
    const double gK = k0 ? g0 : g1, piK = k0 ? pi0 : pi1, qK = k0 ? q0 : q1;
    const double rK = left ? rl : rr, pK = left ? pl : pr, Sw = left ? SL : SR;
    double uK[DIM];
    double kin = 0;
    for (int d = 0; d < DIM; ++d) {
      uK[d] = left ? ul[d] : ur[d];
      kin += uK[d] * uK[d];
    }
    const double unK = uK[D];
    const double rhoE = (pK + gK * piK) / (gK - 1.0) + rK * qK + 0.5 * rK * kin;
    double fm = rK * unK, fmom[DIM], fe = (rhoE + pK) * unK;
    for (int d = 0; d < DIM; ++d) fmom[d] = rK * uK[d] * unK;
    fmom[D] += pK;
    // Inside the fan: F* = F_K + S_K (U*_K - U_K); supersonic, F_K alone.
    const bool supersonic = (left ? SL : -SR) >= 0.0;  // SL >= 0 on the left, SR <= 0 on the right
    const double den = Sw - SM;
    const double fac = (Sw - unK) / (den == 0.0 ? 1.0 : den);
    const double rho_s = rK * fac;
    const double fm_s = fm + Sw * (rho_s - rK);
    double fmom_s[DIM];
    for (int d = 0; d < DIM; ++d) {
      const double us = d == D ? SM : uK[d];
      fmom_s[d] = fmom[d] + Sw * (rho_s * us - rK * uK[d]);
    }
    const double E_s = rho_s * (rhoE / rK + (SM - unK) * (SM + pK / (rK * (Sw - unK))));
    const double fe_s = fe + Sw * (E_s - rhoE);
    fm = supersonic ? fm : fm_s;
    fe = supersonic ? fe : fe_s;
    for (int d = 0; d < DIM; ++d) fmom[d] = supersonic ? fmom[d] : fmom_s[d];
    // Phase 0's Lagrangian terms, into the cell the contact enters (both into the cell for an intra-cell contact).
    const double jump0 = p0 ? -1.0 : 1.0;
    const double la = -S * jump0 * SM, lm = S * jump0 * pstar, le = S * jump0 * pstar * SM;
    if constexpr (INTRA) {
      la_r[f] += la;
      lm_r[f] += lm;
      le_r[f] += le;
    } else {
      la_l[f] = left ? 0.0 : la;
      lm_l[f] = left ? 0.0 : lm;
      le_l[f] = left ? 0.0 : le;
      la_r[f] = left ? la : 0.0;
      lm_r[f] = left ? lm : 0.0;
      le_r[f] = left ? le : 0.0;
      // The flux goes to the phase at x/t = 0: phase 0 where K is phase 0.
      const double m = S * fm;
      F0[0][f] += k0 ? m : 0.0;
      F1[0][f] += k0 ? 0.0 : m;
      for (int d = 0; d < DIM; ++d) {
        const double v = S * fmom[d];
        F0[1 + d][f] += k0 ? v : 0.0;
        F1[1 + d][f] += k0 ? 0.0 : v;
      }
      const double en = S * fe;
      F0[1 + DIM][f] += k0 ? en : 0.0;
      F1[1 + DIM][f] += k0 ? 0.0 : en;
      if (heat) {  // phase 1's material energy per mass, of its state in the pair
        const double r1s = p0 ? rr : rl, pr1 = p0 ? pr : pl;
        heat[f] += (k0 ? 0.0 : m) * ((pr1 + g1 * pi1) / (g1 - 1.0) + r1s * q1) / r1s;
      }
    }
  }
}

}  // namespace cosim::fluid
