// Residual, per face row: MUSCL reconstruction, the limited slopes and the edge states of a row of cells.
#pragma once

#include "fluid_solver/core/solver.h"

namespace cosim::fluid {

template <int DIM, int NP, FluxKind FK>
template <ReconMode RM>
inline double Solver<DIM, NP, FK>::slope(double wm, double w0, double wp) {
  if constexpr (RM == ReconMode::First) {  // first order: the edges are the cell values
    (void)wm, (void)w0, (void)wp;
    return 0.0;
  } else if constexpr (RM == ReconMode::Minmod) return limited_slope<Limiter::Minmod>(w0 - wm, wp - w0);
  else if constexpr (RM == ReconMode::VanLeer) return limited_slope<Limiter::VanLeer>(w0 - wm, wp - w0);
  else return limited_slope<Limiter::MC>(w0 - wm, wp - w0);
}

// The primitive slots that hold a phase's sound speed: edges get it from their rho and p, not by reconstruction.
template <int DIM, int NP, FluxKind FK>
constexpr bool Solver<DIM, NP, FK>::is_sound_var(int v) {
  for (int k = 0; k < NP; ++k)
    if (v == Lay::sound(k)) return true;
  return false;
}

// Limited MUSCL edge states of `count` consecutive cells starting at `first` along direction D.
// Edge buffer layout: for every primitive variable v, lo[v][e] at e + v * len and hi at
// e + (kPrim + v) * len, len = edge_row_len(). Every cell's slopes are computed once per sweep.
template <int DIM, int NP, FluxKind FK>
template <int D, ReconMode RM>
inline void Solver<DIM, NP, FK>::compute_edges(std::size_t first, int count, double* edges) const {
  const std::size_t s = static_cast<std::size_t>(g_.stride[D]), len = edge_row_len();
  for (int v = 0; v < nprim_; ++v) {
    if (is_sound_var(v)) continue;  // from rho and p below
    const double* w = W_.var(v) + first;
    double* lo = edges + v * len;
    double* hi = edges + (Lay::kPrim + v) * len;
    for (int e = 0; e < count; ++e) {
      const double half = 0.5 * slope<RM>(w[e - s], w[e], w[e + s]);
      lo[e] = w[e] - half;
      hi[e] = w[e] + half;
    }
  }
  for (int k = 0; k < NP; ++k)
    for (int side = 0; side < 2; ++side) {
      const std::size_t off = side * Lay::kPrim * len;
      const double* r = edges + off + Lay::rho(k) * len;
      const double* p = edges + off + Lay::pres(k) * len;
      double* c = edges + off + Lay::sound(k) * len;
      const double g = eos_[k].gamma, pinf = eos_[k].pinf;
      for (int e = 0; e < count; ++e) c[e] = std::sqrt(g * (p[e] + pinf) / r[e]);
    }
}

// Phase state of edge e (side 0 = lo, 1 = hi) of an edge row.
template <int DIM, int NP, FluxKind FK>
inline PhaseState<DIM> Solver<DIM, NP, FK>::edge_state(const double* edges, int side, int k, int e) const {
  const std::size_t len = edge_row_len();
  const double* b = edges + side * Lay::kPrim * len + e;
  PhaseState<DIM> st;
  st.rho = b[Lay::rho(k) * len];
  for (int d = 0; d < DIM; ++d) st.u[d] = b[Lay::vel(k, d) * len];
  st.p = b[Lay::pres(k) * len];
  st.c = b[Lay::sound(k) * len];
  return st;
}

template <int DIM, int NP, FluxKind FK>
inline double Solver<DIM, NP, FK>::edge_alpha(const double* edges, int side, int e) const {
  return edges[(side * Lay::kPrim + Lay::palpha) * edge_row_len() + e];
}

}  // namespace cosim::fluid
