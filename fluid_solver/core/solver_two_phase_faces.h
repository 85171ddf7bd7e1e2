// Two-phase face terms: cross contacts, intra-cell Lagrangian, trace-phase faces, the dispersed collision stress.
#pragma once

#include "fluid_solver/core/solver.h"
#include "fluid_solver/flux/cross_row.h"
#include "fluid_solver/physics/particle_stress_row.h"

namespace cosim::fluid {

// The cross contacts of a row's faces and the second-order intra-cell contacts of their right cells, over the
// span of faces where the volume fraction varies (flux/cross_row.h); outside it they are zero.
template <int DIM, int NP, FluxKind FK>
template <int D, ReconMode RM>
inline void Solver<DIM, NP, FK>::cross_faces(int len, const double* left_edges, int left_off, const double* right_edges,
                                             int right_off, double* buf, std::size_t flen) const {
  if constexpr (NP == 2) {
    const std::size_t elen = edge_row_len();
    const double* al = left_edges + (Lay::kPrim + Lay::palpha) * elen + left_off;
    const double* ar = right_edges + Lay::palpha * elen + right_off;
    const double* arhi = right_edges + (Lay::kPrim + Lay::palpha) * elen + right_off;
    const bool intra = RM != ReconMode::First;
    const auto varies = [&](int f) { return al[f] != ar[f] || (intra && ar[f] != arhi[f]); };
    int lo = 0, hi = len;
    while (lo < hi && !varies(lo)) ++lo;
    while (hi > lo && !varies(hi - 1)) --hi;
    if (lo == hi) return;
    // Views of the span: phase k's (rho, u, p, c) on the left cells' hi edges, the right cells' lo and hi edges.
    const double *Lv[2][Lay::kPrimPerPhase], *Rv[2][Lay::kPrimPerPhase], *Hv[2][Lay::kPrimPerPhase];
    for (int k = 0; k < 2; ++k)
      for (int q = 0; q < Lay::kPrimPerPhase; ++q) {
        const int v = Lay::rho(k) + q;
        Lv[k][q] = left_edges + (Lay::kPrim + v) * elen + left_off + lo;
        Rv[k][q] = right_edges + v * elen + right_off + lo;
        Hv[k][q] = right_edges + (Lay::kPrim + v) * elen + right_off + lo;
      }
    double *f0[2 + DIM], *f1[2 + DIM], *lagl[3], *lagr[3];
    for (int q = 0; q < 2 + DIM; ++q) {
      f0[q] = buf + fvar_flux(0, q) * flen + lo;
      f1[q] = buf + fvar_flux(1, q) * flen + lo;
    }
    for (int q = 0; q < 3; ++q) {
      lagl[q] = buf + (fvar_lag_left + q) * flen + lo;
      lagr[q] = buf + (fvar_lag_right + q) * flen + lo;
    }
    CrossRowOut out;
    out.flux0 = f0;
    out.flux1 = f1;
    out.lag_left = lagl;
    out.lag_right = lagr;
    if (gran_) out.heat = buf + fvar_heat * flen + lo;
    const int n = hi - lo;
    cross_row<DIM, D, false>(n, Lv[0], Lv[1], Rv[0], Rv[1], al + lo, ar + lo, eos_, out);
    if (intra) cross_row<DIM, D, true>(n, Rv[0], Rv[1], Hv[0], Hv[1], ar + lo, arhi + lo, eos_, out);
  } else {
    (void)len, (void)left_edges, (void)left_off, (void)right_edges, (void)right_off, (void)buf, (void)flen;
  }
}

// A dispersed phase's collision stress Pi(alpha) at the faces of a row (docs/methods.md §2.8): the centred
// stress in its normal momentum and energy fluxes, with the local Lax-Friedrichs dissipation of its compaction
// waves, -c_f/2 (U+ - U-), c_f = max of the two sides' sqrt(Pi'/rho_p), on its conserved variables.
template <int DIM, int NP, FluxKind FK>
template <int D>
inline void Solver<DIM, NP, FK>::add_particle_stress(int len, const double* left_edges, int left_off,
                                                     const double* right_edges, int right_off, double* buf,
                                                     std::size_t flen) const {
  if constexpr (NP == 2) {
    if (!scene_.exchange.dispersed) return;
    const bool b3 = scene_.exchange.particle_stress.beta == 3.0;
    if (gran_ && b3) particle_stress_row<D, 3, true>(len, left_edges, left_off, right_edges, right_off, buf, flen);
    else if (gran_) particle_stress_row<D, 0, true>(len, left_edges, left_off, right_edges, right_off, buf, flen);
    else if (b3) particle_stress_row<D, 3, false>(len, left_edges, left_off, right_edges, right_off, buf, flen);
    else particle_stress_row<D, 0, false>(len, left_edges, left_off, right_edges, right_off, buf, flen);
  } else {
    (void)len, (void)left_edges, (void)left_off, (void)right_edges, (void)right_off, (void)buf, (void)flen;
  }
}

// The row's edge views for physics/particle_stress_row.h.
template <int DIM, int NP, FluxKind FK>
template <int D, int B, bool GRAN>
inline void Solver<DIM, NP, FK>::particle_stress_row(int len, const double* left_edges, int left_off,
                                                     const double* right_edges, int right_off, double* buf,
                                                     std::size_t flen) const {
  const std::size_t elen = edge_row_len();
  const auto lv = [&](int v) { return left_edges + (Lay::kPrim + v) * elen + left_off; };  // hi edge, left cell
  const auto rv = [&](int v) { return right_edges + v * elen + right_off; };               // lo edge, right cell
  DispersedFaceRow<DIM> r;
  r.alpha_left = lv(Lay::palpha);
  r.alpha_right = rv(Lay::palpha);
  r.rho_left = lv(Lay::rho(1));
  r.rho_right = rv(Lay::rho(1));
  r.p_left = lv(Lay::pres(1));
  r.p_right = rv(Lay::pres(1));
  for (int d = 0; d < DIM; ++d) {
    r.u_left[d] = lv(Lay::vel(1, d));
    r.u_right[d] = rv(Lay::vel(1, d));
    r.flux_mom[d] = buf + fvar_flux(1, 1 + d) * flen;
  }
  r.flux_mass = buf + fvar_flux(1, 0) * flen;
  r.flux_energy = buf + fvar_flux(1, 1 + DIM) * flen;
  if constexpr (GRAN) {
    r.k_left = lv(Lay::pgran);
    r.k_right = rv(Lay::pgran);
    r.flux_heat = buf + fvar_heat * flen;
  }
  // Only the span of the row where the particles are more than a trace (or move at random) on a side of a face:
  // a trace's stress and compaction speed are far below round-off of the flow (skip_below, particle_stress.h).
  const ParticleStress& ps = scene_.exchange.particle_stress;
  int first = 0, last = len;
  if (ps.skip_below > 0.0) {
    const double acut = 1.0 - ps.skip_below;  // carrier fractions above it: a particle trace
    const auto active = [&](int f) {
      bool a = r.alpha_left[f] <= acut || r.alpha_right[f] <= acut;
      if constexpr (GRAN) a = a || r.k_left[f] > kRandomEnergyOfATrace || r.k_right[f] > kRandomEnergyOfATrace;
      return a;
    };
    while (first < len && !active(first)) ++first;
    while (last > first && !active(last - 1)) --last;
    if (first == last) return;
  }
  if (first > 0) r.advance(first);
  add_particle_stress_row<DIM, D, B, GRAN>(last - first, r, ps, scene_.exchange.granular, eos_[NP - 1]);
}

// Faces of a row where phase k is a trace on both sides get the trace flux (flux/trace_flux.h) in place of
// the row kernel's, per unit contact (before the contact-fraction weights): the trace row into `tbuf` (2 + DIM
// rows of flen) wherever a face of the row needs it, then selected face by face, both loops branch-free. The
// views lv / rv are aufs_row's.
template <int DIM, int NP, FluxKind FK>
template <int D>
inline void Solver<DIM, NP, FK>::trace_faces(int k, int len, const double* const* lv, const double* const* rv,
                                             const double* al, const double* ar, double* const* fv, double* tbuf,
                                             std::size_t flen) const {
  const double tr = trace_[k];
  if (tr <= 0.0) return;
  // Phase k's volume fraction is al (phase 0) or 1 - al: a trace on both sides where both are below tr.
  const auto both_trace = [&](int f) {
    const double akL = k == 0 ? al[f] : 1.0 - al[f], akR = k == 0 ? ar[f] : 1.0 - ar[f];
    return akL < tr && akR < tr;
  };
  int lo = 0, hi = len;
  while (lo < hi && !both_trace(lo)) ++lo;
  while (hi > lo && !both_trace(hi - 1)) --hi;
  if (lo == hi) return;
  const double* l[2 + DIM];
  const double* r[2 + DIM];
  double* t[2 + DIM];
  for (int q = 0; q < 2 + DIM; ++q) {
    l[q] = lv[q] + lo;
    r[q] = rv[q] + lo;
    t[q] = tbuf + q * flen + lo;
  }
  trace_row<DIM, D>(hi - lo, l, r, t, eos_[k]);
  for (int q = 0; q < 2 + DIM; ++q) {
    double* out = fv[q];
    const double* tq = tbuf + q * flen;
#pragma GCC ivdep
    for (int f = lo; f < hi; ++f) out[f] = both_trace(f) ? tq[f] : out[f];
  }
}

// Adds the second-order intra-cell Lagrangian term of the face's right cell (docs/methods.md §2.6 step 3).
template <int DIM, int NP, FluxKind FK>
template <int D, ReconMode RM>
inline Lagrangian Solver<DIM, NP, FK>::add_intra_cell(const PhaseState<DIM> (&R)[NP], double aR,
                                                      const double* right_edges, int e, Lagrangian right) const {
  if constexpr (NP == 2 && RM != ReconMode::First) {
    const double aRhi = edge_alpha(right_edges, 1, e);
    if (aR != aRhi) {
      PhaseState<DIM> Rhi[NP];
      for (int k = 0; k < NP; ++k) Rhi[k] = edge_state(right_edges, 1, k, e);
      const Lagrangian in = intra_cell_term<DIM, D>(R, aR, Rhi, aRhi, eos_);
      right.alpha += in.alpha;
      right.mom += in.mom;
      right.energy += in.energy;
    }
  } else {
    (void)R;
    (void)aR;
    (void)right_edges;
    (void)e;
  }
  return right;
}

template <int DIM, int NP, FluxKind FK>
inline void Solver<DIM, NP, FK>::store_lagrangian(double* buf, std::size_t flen, int f, const Lagrangian& left,
                                                  const Lagrangian& right) {
  buf[(fvar_lag_left + 0) * flen + f] = left.alpha;
  buf[(fvar_lag_left + 1) * flen + f] = left.mom;
  buf[(fvar_lag_left + 2) * flen + f] = left.energy;
  buf[(fvar_lag_right + 0) * flen + f] = right.alpha;
  buf[(fvar_lag_right + 1) * flen + f] = right.mom;
  buf[(fvar_lag_right + 2) * flen + f] = right.energy;
}

}  // namespace cosim::fluid
