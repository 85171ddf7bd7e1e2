// Embedded boundary in the residual: ghost states, mirrored wall faces, blocked faces and thin bodies' edges.
#pragma once

#include "fluid_solver/core/solver.h"

namespace cosim::fluid {

// After a step, the ghost and solid-cut cells keep the conservative form of their image-point
// states, so a cell the moving body uncovers is valid at once.
template <int DIM, int NP, FluxKind FK>
inline void Solver<DIM, NP, FK>::store_ghost_states() {
  for (const GhostRecord& gr : emb_.ghosts) {
    const std::size_t c = gr.cell;
    double a0 = 1.0;
    if constexpr (NP == 2) {
      a0 = W_.var(Lay::palpha)[c];
      U_.var(Lay::alpha)[c] = a0;
    }
    for (int k = 0; k < NP; ++k) {
      const double a = k == 0 ? a0 : 1.0 - a0;
      const double rho = W_.var(Lay::rho(k))[c], p = W_.var(Lay::pres(k))[c];
      double q = 0;
      U_.var(Lay::mass(k))[c] = a * rho;
      for (int d = 0; d < DIM; ++d) {
        const double u = W_.var(Lay::vel(k, d))[c];
        U_.var(Lay::mom(k, d))[c] = a * rho * u;
        q += u * u;
      }
      const double rhoe = eos_[k].rho_e(rho, p);
      U_.var(Lay::energy(k))[c] = a * (rhoe + 0.5 * rho * q);
      if constexpr (NP == 2)
        if (k == 1 && gran_) {
          U_.var(Lay::heat)[c] = a * rhoe;
          U_.var(Lay::energy(k))[c] += a * rho * W_.var(Lay::pgran)[c];
        }
    }
  }
}

// Paper steps 5-6 on the reconstructed edge states of one face row: at every face between a
// flow cell and a ghost/solid-cut cell, the solid-side state becomes the mirror of the flow-side
// state about the interface moving with u*: (alpha, rho, u - 2 ((u - u*).n) n, p) per phase, so
// that the face Riemann problem has its contact exactly at u* (docs/methods.md §5.4). u*.n is the
// interface velocity (first order) or its d-weighted extrapolation to the face (eqs. 23-26).
template <int DIM, int NP, FluxKind FK>
template <int D>
inline void Solver<DIM, NP, FK>::mirror_wall_faces(std::size_t base, int len, double* left_edges, int left_off,
                                                   double* right_edges, int right_off) const {
  const auto& faces = emb_.faces[D];
  auto it = std::lower_bound(faces.begin(), faces.end(), base,
                             [](const WallFace& f, std::size_t b) { return high_cell(f) < b; });
  const std::size_t len_e = edge_row_len();
  for (; it != faces.end() && high_cell(*it) < base + static_cast<std::size_t>(len); ++it) {
    const WallFace& wf = *it;
    const int f = static_cast<int>(high_cell(wf) - base);
    // Flow side: hi edge of the low cell or lo edge of the high cell; the solid side gets the mirror.
    const double* from =
        wf.solid_on_high_side ? left_edges + Lay::kPrim * len_e + f + left_off : right_edges + f + right_off;
    double* to = wf.solid_on_high_side ? right_edges + f + right_off : left_edges + Lay::kPrim * len_e + f + left_off;
    mirror_edge(wf, from, to);
  }
}

// Whether phase k's flow over the four cells next to wall face wf (cells 1 to 4 of wall_faces.h, along the
// face's grid line away from the wall) is smooth enough for eq. 25's extrapolation of the wall velocity
// (docs/methods.md §5.5). Eq. 25 is a Taylor expansion from cells 1 and 2 to the face; a shock in these cells
// (MUSCL spreads it over about three) gives slopes the paper's minmod(s, s2) does not limit, and where d is small
// the half-cell extrapolation of the jump moves the face into the gas (the 9.5 panel at 50^2: 37% too much
// velocity, docs/deformable_structures.md). Not smooth: the gas converges between cells 4 and 1 (u_1 > u_4 along
// the normal; a shock, arriving or leaving, always compresses) and their pressures differ by more than
// kWallSmoothPressureSpread of p + p_inf (20%: the jump of a Mach 1.08 shock at gamma 1.4). There the face takes
// the wall's velocity (first order). Expansions never steepen into shocks and keep eq. 25 however steep (a
// receding wall's rarefaction spans more than 20% over four cells at 40 cells, EmbeddedSmoothPiston.*).
template <int DIM, int NP, FluxKind FK>
inline bool Solver<DIM, NP, FK>::smooth_next_to_wall(const WallFace& wf, int k) const {
  double u1 = 0, u4 = 0;
  for (int d = 0; d < DIM; ++d) {
    u1 += W_.var(Lay::vel(k, d))[wf.fluid_cell] * wf.normal[d];
    u4 += W_.var(Lay::vel(k, d))[wf.fluid_cell4] * wf.normal[d];
  }
  if (u1 <= u4) return true;
  const double* p = W_.var(Lay::pres(k));
  const double pinf = eos_[k].pinf;
  double lo = p[wf.fluid_cell] + pinf, hi = lo;
  for (std::size_t c : {wf.fluid_cell2, wf.fluid_cell3, wf.fluid_cell4}) {
    lo = std::min(lo, p[c] + pinf);
    hi = std::max(hi, p[c] + pinf);
  }
  return hi - lo <= kWallSmoothPressureSpread * lo;
}

// The mirror of the flow-side edge state `from` about the interface of wall face wf into `to` (both with the
// edge rows' variable stride): (alpha, rho, u - 2 ((u - u*).n) n, p) per phase, u*.n the interface
// velocity or its d-weighted extrapolation to the face (eqs. 23-26).
template <int DIM, int NP, FluxKind FK>
inline void Solver<DIM, NP, FK>::mirror_edge(const WallFace& wf, const double* from, double* to) const {
  const std::size_t len_e = edge_row_len();
  for (int v = 0; v < Lay::kPrim; ++v) to[v * len_e] = from[v * len_e];
  for (int k = 0; k < NP; ++k) {
    double un = 0, uIn = 0;
    for (int d = 0; d < DIM; ++d) {
      un += from[Lay::vel(k, d) * len_e] * wf.normal[d];
      uIn += wf.wall_velocity[d] * wf.normal[d];
    }
    double ustar = uIn;
    if (wall_second_order_ && smooth_next_to_wall(wf, k)) {  // eqs. 23, 25, 26 with the paper's minmod
      double u1 = 0, u2 = 0;
      for (int d = 0; d < DIM; ++d) {
        u1 += W_.var(Lay::vel(k, d))[wf.fluid_cell] * wf.normal[d];
        u2 += W_.var(Lay::vel(k, d))[wf.fluid_cell2] * wf.normal[d];
      }
      const double s = (uIn - u1) + (1.0 - wf.d) / (1.0 + wf.d) * (uIn - u2);
      ustar = uIn + (0.5 - wf.d) * limited_slope<Limiter::Minmod>(s, u1 - u2);
    }
    for (int d = 0; d < DIM; ++d) to[Lay::vel(k, d) * len_e] -= 2.0 * (un - ustar) * wf.normal[d];
  }
}

// Blocked faces (a body thinner than a cell between two flow cells) of one face row: the face buffer gets the
// wall flux of the high cell (its mirrored lo edge | its lo edge) before apply_right, and that of the low cell
// (its hi edge | the mirror) before apply_left. Same arguments as mirror_wall_faces.
template <int DIM, int NP, FluxKind FK>
template <int D, ReconMode RM>
inline void Solver<DIM, NP, FK>::blocked_face_fluxes(bool high_side, std::size_t base, int len,
                                                     const double* left_edges, int left_off, const double* right_edges,
                                                     int right_off, Scratch& sc, double* buf, std::size_t flen) {
  const auto& faces = emb_.blocked[D];
  if (faces.empty()) return;
  auto it = std::lower_bound(faces.begin(), faces.end(), base,
                             [](const BlockedFace& f, std::size_t b) { return f.high.fluid_cell < b; });
  const std::size_t len_e = edge_row_len(), hi = Lay::kPrim * len_e;
  double* mini = sc.mini;
  double* face1 = sc.face1;
  const double area = g_.cell_volume() / g_.dx[D];
  // One-face row in the scratch edges: face 0 = (hi edge of edge 0 | lo edge of edge 1); edge 1's hi edge is
  // the right cell's other edge (its intra-cell term, two phases).
  double* m0hi = mini + hi;
  double* m1lo = mini + 1;
  double* m1hi = mini + hi + 1;
  for (; it != faces.end() && it->high.fluid_cell < base + static_cast<std::size_t>(len); ++it) {
    const int f = static_cast<int>(it->high.fluid_cell - base);
    if (high_side) {
      const double* lo_edge = right_edges + f + right_off;
      for (int v = 0; v < Lay::kPrim; ++v) {
        m1lo[v * len_e] = lo_edge[v * len_e];
        m1hi[v * len_e] = lo_edge[hi + v * len_e];
      }
      mirror_edge(it->high, lo_edge, m0hi);
    } else {
      const double* hi_edge = left_edges + hi + f + left_off;
      for (int v = 0; v < Lay::kPrim; ++v) m0hi[v * len_e] = hi_edge[v * len_e];
      mirror_edge(it->low, hi_edge, m1lo);
      for (int v = 0; v < Lay::kPrim; ++v) m1hi[v * len_e] = m1lo[v * len_e];
    }
    compute_faces<D, RM>(1, mini, 0, mini, 1, face1, 1);
    // In the wall exchange account on the block that owns the flow cell (Grid::owns; the x rows reach a ghost cell).
    const WallFace& wf = high_side ? it->high : it->low;
    wall_face_flux(sc, wf, D, high_side ? 1.0 : -1.0, g_.owns(wf.fluid_cell) ? area : 0.0, face1, 1, 0);
    for (int v = 0; v < kFaceVars; ++v) buf[v * flen + f] = face1[v];
  }
}

// Thin bodies: the flow cells with side ghosts along D among the `count` cells from `first` get their edges
// again, with the side ghost in place of the cell across the body (compute_edges' layout).
template <int DIM, int NP, FluxKind FK>
template <int D, ReconMode RM>
inline void Solver<DIM, NP, FK>::fix_side_edges(std::size_t first, int count, double* edges) const {
  const auto& sgs = emb_.side_ghosts[D];
  if (sgs.empty()) return;
  const std::size_t s = static_cast<std::size_t>(g_.stride[D]), len = edge_row_len();
  auto it = std::lower_bound(sgs.begin(), sgs.end(), first,
                             [](const SideGhost& g, std::size_t c) { return g.flow_cell < c; });
  const double* values = side_values_[D].data();
  while (it != sgs.end() && it->flow_cell < first + static_cast<std::size_t>(count)) {
    const std::size_t c = it->flow_cell;
    const double *below = nullptr, *above = nullptr;
    for (; it != sgs.end() && it->flow_cell == c; ++it)
      (it->across_high ? above : below) = values + static_cast<std::size_t>(it - sgs.begin()) * Lay::kPrim;
    const std::size_t e = c - first;
    for (int v = 0; v < nprim_; ++v) {
      if (is_sound_var(v)) continue;
      const double* w = W_.var(v);
      const double wm = below ? below[v] : w[c - s], wp = above ? above[v] : w[c + s];
      const double half = 0.5 * slope<RM>(wm, w[c], wp);
      edges[v * len + e] = w[c] - half;
      edges[(Lay::kPrim + v) * len + e] = w[c] + half;
    }
    for (int k = 0; k < NP; ++k)
      for (int side = 0; side < 2; ++side) {
        double* b = edges + side * Lay::kPrim * len + e;
        b[Lay::sound(k) * len] = eos_[k].sound_speed(b[Lay::rho(k) * len], b[Lay::pres(k) * len]);
      }
  }
}

}  // namespace cosim::fluid
