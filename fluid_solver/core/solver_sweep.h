// Residual: the directional sweeps, the face-row fluxes and their application to the cells (apply_right/left).
#pragma once

#include "fluid_solver/core/solver.h"
#include "fluid_solver/flux/aufs_row.h"

namespace cosim::fluid {

// The x faces of one row of cells from `base` into `faces`, with its edges in `edges`, added to R (assigned in 1D).
template <int DIM, int NP, FluxKind FK>
template <ReconMode RM>
inline void Solver<DIM, NP, FK>::x_row(Scratch& sc, std::size_t base, double* edges, double* faces) {
  const double inv_dx = 1.0 / g_.dx[0];
  const int n0 = g_.n[0];
  const std::size_t flen = static_cast<std::size_t>(n0 + 1);
  // Edge index e <-> cell base - 1 + e; face f has left edge row index f, right f + 1.
  {
    PassClock clk(pass_acc(Pass::Reconstruction));
    compute_edges<0, RM>(base - 1, n0 + 2, edges);
    if (emb_.active) {
      fix_side_edges<0, RM>(base - 1, n0 + 2, edges);
      mirror_wall_faces<0>(base, n0 + 1, edges, 0, edges, 1);
    }
  }
  {
    PassClock clk(pass_acc(Pass::Fluxes));
    compute_faces<0, RM>(n0 + 1, edges, 0, edges, 1, faces, flen);
    if (emb_.active) wall_face_row<0>(sc, base, n0 + 1, faces, flen, true, true);
  }
  const auto blocked = [&](bool high_side) {
    PassClock clk(pass_acc(Pass::Fluxes), pass_acc(Pass::Apply));
    blocked_face_fluxes<0, RM>(high_side, base, n0 + 1, edges, 0, edges, 1, sc, faces, flen);
  };
  PassClock clk(pass_acc(Pass::Apply));
  if (domain_edge_[0][0]) add_boundary_flux<0>(sc, faces, flen, 0, base, 1);
  if (domain_edge_[0][1]) add_boundary_flux<0>(sc, faces, flen, n0, base + n0 - 1, -1);
  if (emb_.active && emb_.blocked_x) {  // a blocked face's two cells get different fluxes (somewhere in the mesh)
    blocked(true);
    apply_right<0, DIM == 1>(faces, flen, base, 0, n0, inv_dx);
    blocked(false);
    apply_left<0>(faces, flen, base - 1, 1, n0 + 1, inv_dx);
  } else {  // cell i between faces i and i + 1 of the row
    apply_cells<0, DIM == 1>(faces, faces + 1, flen, base, n0, inv_dx);
  }
}

// Sweep along D over all face rows, handing every cell row that it completes to row_done(Scratch&, base, len,
// primitives_now). In 1D the x sweep is all there is. Else the last transverse sweep processed (z in 3D; y in 2D,
// where it assigns R) goes first, and the y sweep finishes each cell row as soon as its two face rows are known:
// the row's x faces (x_row), then row_done. The primitives of the two rows next to a chunk's ends must wait
// (primitives_now false): the neighbouring chunk's slopes read them (deferred_primitives).
template <int DIM, int NP, FluxKind FK>
template <int D, ReconMode RM, class RowDone>
inline void Solver<DIM, NP, FK>::sweep_impl(RowDone& row_done) {
  const double inv_dx = 1.0 / g_.dx[D];
  const std::size_t s = static_cast<std::size_t>(g_.stride[D]);
  const int n0 = g_.n[0];
  const std::size_t flen = static_cast<std::size_t>(n0 + 1);
  if constexpr (D == 0) {
    static_assert(DIM == 1, "the x sweep runs inside the y sweep");
    const int rows = g_.n[1] * g_.n[2];
#pragma omp parallel for schedule(static)
    for (int row = 0; row < rows; ++row) {
      Scratch& sc = scratch_[static_cast<std::size_t>(omp_get_thread_num())];
      const std::size_t base = g_.index(0, row % g_.n[1], row / g_.n[1]);
      x_row<RM>(sc, base, sc.edges[0], sc.faces);
      row_done(sc, base, n0, true);
    }
  } else {
    const int nD = g_.n[D];
    const int others = D == 1 ? g_.n[2] : g_.n[1];
    const int chunks = sweep_chunks<D>(), tasks = others * chunks;
#pragma omp parallel for schedule(static)
    for (int t = 0; t < tasks; ++t) {
      Scratch& sc = scratch_[static_cast<std::size_t>(omp_get_thread_num())];
      const int o = t / chunks, ch = t % chunks;
      const int a = static_cast<int>(static_cast<long>(ch) * nD / chunks);
      const int b = static_cast<int>(static_cast<long>(ch + 1) * nD / chunks);
      auto row_base = [&](int layer) { return D == 1 ? g_.index(0, layer, o) : g_.index(0, o, layer); };
      // Edge rows alternate between the two buffers: `prev` holds the cell row below the face layer; so do
      // the face rows: `low` holds the faces below that cell row, `high` those above it.
      int prev = 0;
      double* low = sc.faces;
      double* high = sc.faces2;
      {
        PassClock clk(pass_acc(Pass::Reconstruction));
        compute_edges<D, RM>(row_base(a - 1), n0, sc.edges[prev]);
        if (emb_.active) fix_side_edges<D, RM>(row_base(a - 1), n0, sc.edges[prev]);
      }
      for (int layer = a; layer <= b; ++layer) {
        const std::size_t base = row_base(layer);
        {
          PassClock clk(pass_acc(Pass::Reconstruction));
          compute_edges<D, RM>(base, n0, sc.edges[1 - prev]);
          if (emb_.active) {
            fix_side_edges<D, RM>(base, n0, sc.edges[1 - prev]);
            mirror_wall_faces<D>(base, n0, sc.edges[prev], 0, sc.edges[1 - prev], 0);
          }
        }
        {
          PassClock clk(pass_acc(Pass::Fluxes));
          compute_faces<D, RM>(n0, sc.edges[prev], 0, sc.edges[1 - prev], 0, high, flen);
          if (emb_.active) wall_face_row<D>(sc, base, n0, high, flen, layer > a, layer < b);
        }
        // A blocked face's buffer entry holds the wall flux of the cell below it (high_side false) or above it.
        const auto blocked = [&](bool high_side) {
          if (emb_.active) {
            PassClock clk(pass_acc(Pass::Fluxes), pass_acc(Pass::Apply));
            blocked_face_fluxes<D, RM>(high_side, base, n0, sc.edges[prev], 0, sc.edges[1 - prev], 0, sc, high, flen);
          }
        };
        {
          PassClock clk(pass_acc(Pass::Apply));
          if (layer == 0 && domain_edge_[D][0])
            for (int f = 0; f < n0; ++f) add_boundary_flux<D>(sc, high, flen, f, base + f, 1);
          if (layer == nD && domain_edge_[D][1])
            for (int f = 0; f < n0; ++f) add_boundary_flux<D>(sc, high, flen, f, base - s + f, -1);
          if (layer > a) {  // the cell row below is complete: both of its face rows are known
            blocked(false);
            apply_cells<D, D == DIM - 1>(low, high, flen, base - s, n0, inv_dx);
          }
          if (layer < b) blocked(true);  // for the cell row above, next layer
        }
        if constexpr (D == 1)
          if (layer > a) {
            x_row<RM>(sc, base - s, sc.xedges, sc.xfaces);
            row_done(sc, base - s, n0, layer - 1 >= a + 2 && layer - 1 < b - 2);
          }
        std::swap(low, high);
        prev = 1 - prev;
      }
    }
  }
}

// Faces f in [0, len) of a row. Left states: hi edges of
// `left_edges` at f + left_off; right states: lo edges of `right_edges` at f + right_off.
template <int DIM, int NP, FluxKind FK>
template <int D, ReconMode RM>
inline void Solver<DIM, NP, FK>::compute_faces(int len, const double* left_edges, int left_off,
                                               const double* right_edges, int right_off, double* buf,
                                               std::size_t flen) {
  const bool lowmach = scene_.low_mach;
  const double cutoff = scene_.low_mach_cutoff;
  // Face f's reconstructed left/right phase states and phase-0 volume fractions.
  auto load_face = [&](int f, PhaseState<DIM>(&L)[NP], PhaseState<DIM>(&R)[NP], double& aL, double& aR) {
    aL = aR = 1.0;
    for (int k = 0; k < NP; ++k) {
      L[k] = edge_state(left_edges, 1, k, f + left_off);
      R[k] = edge_state(right_edges, 0, k, f + right_off);
    }
    if constexpr (NP == 2) {
      aL = edge_alpha(left_edges, 1, f + left_off);
      aR = edge_alpha(right_edges, 0, f + right_off);
    }
  };
  if constexpr (FK == FluxKind::AUFS) {
    // Same-phase contacts with the vectorised AUFS row kernel, one phase at a time.
    const std::size_t elen = edge_row_len();
    for (int k = 0; k < NP; ++k) {
      const double* lv[Lay::kPrimPerPhase];
      const double* rv[Lay::kPrimPerPhase];
      double* fv[2 + DIM];
      for (int q = 0; q < Lay::kPrimPerPhase; ++q) {
        const int v = Lay::rho(k) + q;
        lv[q] = left_edges + (Lay::kPrim + v) * elen + left_off;
        rv[q] = right_edges + v * elen + right_off;
      }
      for (int q = 0; q < 2 + DIM; ++q) fv[q] = buf + fvar_flux(k, q) * flen;
      if (trace_[k] > 1.0) {  // a dispersed phase: the trace flux everywhere
        if (gran_)
          trace_row<DIM, D, true>(len, lv, rv, fv, eos_[k], left_edges + (Lay::kPrim + Lay::pgran) * elen + left_off,
                                  right_edges + Lay::pgran * elen + right_off, buf + fvar_heat * flen);
        else trace_row<DIM, D>(len, lv, rv, fv, eos_[k]);
        continue;
      }
      if (lowmach) aufs_row<DIM, D, true>(len, lv, rv, fv, eos_[k], cutoff);
      else aufs_row<DIM, D, false>(len, lv, rv, fv, eos_[k], cutoff);
      if constexpr (NP == 2)
        trace_faces<D>(k, len, lv, rv, left_edges + (Lay::kPrim + Lay::palpha) * elen + left_off,
                       right_edges + Lay::palpha * elen + right_off, fv,
                       scratch_[static_cast<std::size_t>(omp_get_thread_num())].trace, flen);
    }
    if constexpr (NP == 2) {
      // Weight by the same-phase contact fractions S_kk = min(alpha_k-, alpha_k+).
      const double* al = left_edges + (Lay::kPrim + Lay::palpha) * elen + left_off;
      const double* ar = right_edges + Lay::palpha * elen + right_off;
      for (int q = 0; q < 2 + DIM; ++q) {
        double* f0 = buf + fvar_flux(0, q) * flen;
        double* f1 = buf + fvar_flux(1, q) * flen;
#pragma GCC ivdep
        for (int f = 0; f < len; ++f) {
          f0[f] *= std::min(al[f], ar[f]);
          f1[f] *= std::min(1.0 - al[f], 1.0 - ar[f]);
        }
      }
      if (gran_) {
        double* fh = buf + fvar_heat * flen;
#pragma GCC ivdep
        for (int f = 0; f < len; ++f) fh[f] *= std::min(1.0 - al[f], 1.0 - ar[f]);
      }
      std::fill_n(buf + fvar_lag_left * flen, 6 * flen, 0.0);
      cross_faces<D, RM>(len, left_edges, left_off, right_edges, right_off, buf, flen);
    }
    add_particle_stress<D>(len, left_edges, left_off, right_edges, right_off, buf, flen);
    return;
  }
  for (int f = 0; f < len; ++f) {
    PhaseState<DIM> L[NP], R[NP];
    double aL, aR;
    load_face(f, L, R, aL, aR);
    FaceResult<DIM, NP> res;
    if (lowmach) {
      PhaseState<DIM> sL[NP], sR[NP];
      for (int k = 0; k < NP; ++k) {
        sL[k] = L[k];
        sR[k] = R[k];
        const double amin = k == 0 ? std::min(aL, aR) : std::min(1.0 - aL, 1.0 - aR);
        if (amin > 1e-6) low_mach_correction<DIM>(sL[k].u, sL[k].c, sR[k].u, sR[k].c, cutoff);
      }
      dem_face<FK, DIM, NP, D>(L, R, sL, sR, aL, aR, eos_, res, trace_.data());
    } else {
      dem_face<FK, DIM, NP, D>(L, R, L, R, aL, aR, eos_, res, trace_.data());
    }
    for (int k = 0; k < NP; ++k) {
      buf[fvar_flux(k, 0) * flen + f] = res.flux[k].mass;
      for (int d = 0; d < DIM; ++d) buf[fvar_flux(k, 1 + d) * flen + f] = res.flux[k].mom[d];
      buf[fvar_flux(k, 1 + DIM) * flen + f] = res.flux[k].energy;
    }
    if constexpr (NP == 2)
      store_lagrangian(buf, flen, f, res.to_left,
                       add_intra_cell<D, RM>(R, aR, right_edges, f + right_off, res.to_right));
  }
  add_particle_stress<D>(len, left_edges, left_off, right_edges, right_off, buf, flen);
}

// A domain-boundary face f of a face row whose interior cell is `cell`: sign +1 when the flux along +e_D
// enters the domain (the low boundary), -1 at the high one; times the face area. Faces next to a body's
// cell (not a flow cell) carry nothing into the flow cells.
template <int DIM, int NP, FluxKind FK>
template <int D>
inline void Solver<DIM, NP, FK>::add_boundary_flux(Scratch& sc, const double* buf, std::size_t flen, int f,
                                                   std::size_t cell, int sign) const {
  if (emb_.active && !is_flow_cell(emb_.kind[cell])) return;
  const double area = sign * g_.cell_volume() / g_.dx[D];
  for (int k = 0; k < NP; ++k)
    for (int q = 0; q < 2 + DIM; ++q) sc.boundary[fvar_flux(k, q)] += area * buf[fvar_flux(k, q) * flen + f];
}

// Cells [base, base + n) of a row between the face rows `low` (their low faces) and `high` (their high faces),
// both laid out as the face-row buffer: R += (F_low - F_high) / dx, and the Lagrangian parts that the faces hand
// to the cell (the low face's right part, the high face's left part); the first sweep assigns (ASSIGN).
template <int DIM, int NP, FluxKind FK>
template <int D, bool ASSIGN>
inline void Solver<DIM, NP, FK>::apply_cells(const double* low, const double* high, std::size_t flen, std::size_t base,
                                             int n, double inv_dx) {
  const auto difference = [&](int rvar, int fvar) {
    double* r = R_.var(rvar) + base;
    const double* fl = low + fvar * flen;
    const double* fh = high + fvar * flen;
    if constexpr (ASSIGN)
      for (int i = 0; i < n; ++i) r[i] = inv_dx * (fl[i] - fh[i]);
    else
      for (int i = 0; i < n; ++i) r[i] += inv_dx * (fl[i] - fh[i]);
  };
  for (int k = 0; k < NP; ++k)
    for (int q = 0; q < 2 + DIM; ++q) difference(Lay::mass(k) + q, fvar_flux(k, q));
  if constexpr (NP == 2) {
    if (gran_) difference(Lay::heat, fvar_heat);
    // Phase 0 gets +Lag, phase 1 gets -Lag (its [X_k] is opposite); momentum along the face normal.
    double* ra = R_.var(Lay::alpha) + base;
    double* rm0 = R_.var(Lay::mom(0, D)) + base;
    double* rm1 = R_.var(Lay::mom(NP - 1, D)) + base;
    double* re0 = R_.var(Lay::energy(0)) + base;
    double* re1 = R_.var(Lay::energy(NP - 1)) + base;
    const double* lr = low + fvar_lag_right * flen;
    const double* ll = high + fvar_lag_left * flen;
    for (int i = 0; i < n; ++i) {
      const double la = inv_dx * (lr[i] + ll[i]);
      const double lm = inv_dx * (lr[flen + i] + ll[flen + i]);
      const double le = inv_dx * (lr[2 * flen + i] + ll[2 * flen + i]);
      ra[i] = ASSIGN ? la : ra[i] + la;
      rm0[i] += lm;
      rm1[i] -= lm;
      re0[i] += le;
      re1[i] -= le;
    }
  }
}

// Faces f in [f0, f1) of the row add (F + Lag_right) to cell rbase + f (rows with blocked faces). The first sweep
// assigns instead (ASSIGN), which saves a pass that zeroes the residual.
template <int DIM, int NP, FluxKind FK>
template <int D, bool ASSIGN>
inline void Solver<DIM, NP, FK>::apply_right(const double* buf, std::size_t flen, std::size_t rbase, int f0, int f1,
                                             double inv_dx) {
  for (int k = 0; k < NP; ++k)
    for (int q = 0; q < 2 + DIM; ++q) {
      double* r = R_.var(Lay::mass(k) + q) + rbase;
      const double* F = buf + fvar_flux(k, q) * flen;
      if constexpr (ASSIGN)
        for (int f = f0; f < f1; ++f) r[f] = inv_dx * F[f];
      else
        for (int f = f0; f < f1; ++f) r[f] += inv_dx * F[f];
    }
  if constexpr (NP == 2) {
    if constexpr (ASSIGN) std::fill(R_.var(Lay::alpha) + rbase + f0, R_.var(Lay::alpha) + rbase + f1, 0.0);
    apply_lagrangian<D>(buf + fvar_lag_right * flen, flen, rbase, f0, f1, inv_dx);
    if (gran_) {
      double* r = R_.var(Lay::heat) + rbase;
      const double* F = buf + fvar_heat * flen;
      if constexpr (ASSIGN)
        for (int f = f0; f < f1; ++f) r[f] = inv_dx * F[f];
      else
        for (int f = f0; f < f1; ++f) r[f] += inv_dx * F[f];
    }
  }
}

// Faces f in [f0, f1) subtract F and add Lag_left to cell lbase + f.
template <int DIM, int NP, FluxKind FK>
template <int D>
inline void Solver<DIM, NP, FK>::apply_left(const double* buf, std::size_t flen, std::size_t lbase, int f0, int f1,
                                            double inv_dx) {
  for (int k = 0; k < NP; ++k)
    for (int q = 0; q < 2 + DIM; ++q) {
      double* r = R_.var(Lay::mass(k) + q) + lbase;
      const double* F = buf + fvar_flux(k, q) * flen;
      for (int f = f0; f < f1; ++f) r[f] -= inv_dx * F[f];
    }
  if constexpr (NP == 2) {
    apply_lagrangian<D>(buf + fvar_lag_left * flen, flen, lbase, f0, f1, inv_dx);
    if (gran_) {
      double* r = R_.var(Lay::heat) + lbase;
      const double* F = buf + fvar_heat * flen;
      for (int f = f0; f < f1; ++f) r[f] -= inv_dx * F[f];
    }
  }
}

// Phase 0 gets +Lag, phase 1 gets -Lag (its [X_k] is opposite); momentum along the face normal.
template <int DIM, int NP, FluxKind FK>
template <int D>
inline void Solver<DIM, NP, FK>::apply_lagrangian(const double* lag, std::size_t flen, std::size_t base, int f0, int f1,
                                                  double inv_dx) {
  double* ra = R_.var(Lay::alpha) + base;
  double* rm0 = R_.var(Lay::mom(0, D)) + base;
  double* rm1 = R_.var(Lay::mom(NP - 1, D)) + base;
  double* re0 = R_.var(Lay::energy(0)) + base;
  double* re1 = R_.var(Lay::energy(NP - 1)) + base;
  const double* la = lag;
  const double* lm = lag + flen;
  const double* le = lag + 2 * flen;
  for (int f = f0; f < f1; ++f) {
    ra[f] += inv_dx * la[f];
    rm0[f] += inv_dx * lm[f];
    rm1[f] -= inv_dx * lm[f];
    re0[f] += inv_dx * le[f];
    re1[f] -= inv_dx * le[f];
  }
}

}  // namespace cosim::fluid
