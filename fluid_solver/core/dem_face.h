// Face contributions of the Discrete Equation Method (docs/methods.md §2.3-2.4, §2.6; Abgrall & Saurel
// 2003, Chinnayya et al. 2004) for one face with normal e_D, left state "-" and right state "+".
//
// Same-phase contacts (k,k) carry only a conservative flux (the scene's flux: AUFS by default).
// Cross contacts (p,q), p != q, are two-material Riemann problems solved with HLLC: the phase
// occupying x/t = 0 gets the conservative flux, and the contact moving into the downwind cell
// adds the Lagrangian flux S_pq [X_k] (-u*, 0, p* e_D, p* u*) there. [X_1] = -[X_0], so only
// phase 0's Lagrangian part is stored.
#pragma once

#include <algorithm>

#include "fluid_solver/flux/hllc.h"
#include "fluid_solver/flux/same_phase_flux.h"
#include "fluid_solver/flux/trace_flux.h"

namespace cosim::fluid {

// Lagrangian contribution of phase 0: volume fraction, normal momentum, energy.
struct Lagrangian {
  double alpha = 0, mom = 0, energy = 0;
};

template <int DIM, int NP>
struct FaceResult {
  PhaseFlux<DIM> flux[NP];
  Lagrangian to_left, to_right;  // phase 0 contributions into the left / right cell
};

// Pair (p left, q right) with contact fraction S > 0 (p != q).
template <int DIM, int NP, int D>
inline void cross_pair(const PhaseState<DIM>& Wp, const eos::StiffenedGas& ep, int p, const PhaseState<DIM>& Wq,
                       const eos::StiffenedGas& eq, double S, FaceResult<DIM, NP>& r) {
  const HllcResult<DIM> h = hllc_flux<DIM, D>(Wp, ep, Wq, eq);
  const int owner = h.ustar > 0.0 ? p : 1 - p;  // phase at x/t = 0 (docs/methods.md §2.3(c))
  PhaseFlux<DIM>& f = r.flux[owner];
  f.mass += S * h.flux.mass;
  for (int d = 0; d < DIM; ++d) f.mom[d] += S * h.flux.mom[d];
  f.energy += S * h.flux.energy;
  const double jump0 = p == 0 ? -1.0 : 1.0;                  // [X_0] = delta_0q - delta_0p
  Lagrangian& lag = h.ustar > 0.0 ? r.to_right : r.to_left;  // the cell the contact enters
  lag.alpha += -S * jump0 * h.ustar;
  lag.mom += S * jump0 * h.pstar;
  lag.energy += S * jump0 * h.pstar * h.ustar;
}

// Full DEM face. `same_*` are the states used for the same-phase contacts (low-Mach corrected when
// enabled), `L`/`R` the plain reconstructed states used for the cross contacts. A phase whose volume
// fraction is below `trace_alpha[k]` on both sides gets the trace flux for its same-phase contact.
template <FluxKind FK, int DIM, int NP, int D>
inline void dem_face(const PhaseState<DIM> (&L)[NP], const PhaseState<DIM> (&R)[NP], const PhaseState<DIM> (&sameL)[NP],
                     const PhaseState<DIM> (&sameR)[NP], double aL, double aR, const eos::StiffenedGas* eos,
                     FaceResult<DIM, NP>& r, const double* trace_alpha = nullptr) {
  if constexpr (NP == 1) {
    r.flux[0] = same_phase_flux<FK, DIM, D>(sameL[0], sameR[0], eos[0]);
  } else {
    // Contact fractions (docs/methods.md §2.3(a)).
    const double S00 = std::min(aL, aR), S11 = std::min(1.0 - aL, 1.0 - aR);
    const double S01 = std::max(0.0, aL - aR), S10 = std::max(0.0, aR - aL);
    for (int k = 0; k < NP; ++k) r.flux[k] = PhaseFlux<DIM>{};
    r.to_left = r.to_right = Lagrangian{};
    const double Skk[2] = {S00, S11};
    for (int k = 0; k < NP; ++k) {
      if (Skk[k] <= 0.0) continue;
      const double amax = k == 0 ? std::max(aL, aR) : 1.0 - Skk[0];  // max(1 - aL, 1 - aR)
      const PhaseFlux<DIM> f = trace_alpha && amax < trace_alpha[k]
                                   ? trace_flux<DIM, D>(L[k], R[k], eos[k])
                                   : same_phase_flux<FK, DIM, D>(sameL[k], sameR[k], eos[k]);
      r.flux[k].mass += Skk[k] * f.mass;
      for (int d = 0; d < DIM; ++d) r.flux[k].mom[d] += Skk[k] * f.mom[d];
      r.flux[k].energy += Skk[k] * f.energy;
    }
    if (S01 > 0.0) cross_pair<DIM, NP, D>(L[0], eos[0], 0, R[1], eos[1], S01, r);
    if (S10 > 0.0) cross_pair<DIM, NP, D>(L[1], eos[1], 1, R[0], eos[0], S10, r);
  }
}

// Intra-cell Lagrangian term of second-order DEM (docs/methods.md §2.6 step 3): the cross contacts
// between a cell's left-edge state (m) and right-edge state (p) both lie inside the cell.
template <int DIM, int D>
inline Lagrangian intra_cell_term(const PhaseState<DIM> (&Wm)[2], double am, const PhaseState<DIM> (&Wp)[2], double ap,
                                  const eos::StiffenedGas* eos) {
  FaceResult<DIM, 2> r;
  r.to_left = r.to_right = Lagrangian{};
  const double S01 = std::max(0.0, am - ap), S10 = std::max(0.0, ap - am);
  if (S01 > 0.0) cross_pair<DIM, 2, D>(Wm[0], eos[0], 0, Wp[1], eos[1], S01, r);
  if (S10 > 0.0) cross_pair<DIM, 2, D>(Wm[1], eos[1], 1, Wp[0], eos[0], S10, r);
  return {r.to_left.alpha + r.to_right.alpha, r.to_left.mom + r.to_right.mom, r.to_left.energy + r.to_right.energy};
}

}  // namespace cosim::fluid
