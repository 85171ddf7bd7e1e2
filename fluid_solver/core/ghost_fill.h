// Ghost and solid-cut cells from image points (paper section 8, step 3; docs/methods.md §5.3): every
// phase's density, pressure and volume fraction are interpolated at the image point; the velocity
// keeps the interpolated tangential part and its normal part relative to the wall is extrapolated
// linearly through the wall (u_G,n - u_w,n = -d_G/(L - d_G) (u_IP,n - u_w,n); the mirror image
// point L = 2 d_G gives the reflection 2 u_w,n - u_IP,n), per phase.
// Where the wall pressure p_I is known (GhostRecord::has_wall_pressure), the pressure is extrapolated through the wall
// the same way, p_G = p_IP - L/(L - d_G) (p_IP - p_I), and the density along the isentrope of the image point: an
// accelerating wall (dp/dn = -rho a_n, Euler's equation) or a curved one (dp/dn = rho u_t^2 / R) has a pressure
// gradient at the wall that the even copy p_G = p_IP would remove, a first-order error at the boundary. p_G + p_inf is
// kept within [1/2, 2] x (p_IP + p_inf), so a strong wave at the wall cannot make the ghost inadmissible.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "common/eos/stiffened_gas.h"
#include "fluid_solver/core/embedded_state.h"
#include "fluid_solver/core/layout.h"

namespace cosim::fluid {

// The state of one record from the current primitives W into v[kPrim]; false (v untouched) without a stencil.
template <int DIM, int NP>
bool ghost_state(const GhostRecord& g, const FieldArray& W, const eos::StiffenedGas* eos, double* v) {
  using Lay = Layout<DIM, NP>;
  if (g.stencil_size == 0) return false;
  for (int q = 0; q < Lay::kPrim; ++q) v[q] = 0.0;
  for (int s = 0; s < g.stencil_size; ++s)
    for (int q = 0; q < W.vars; ++q) v[q] += g.weights[s] * W.var(q)[g.stencil[s]];
  const double L = g.image_distance, dG = g.distance;
  const double factor = L > dG ? L / (L - dG) : 2.0;  // 1 + d_G / (L - d_G)
  for (int k = 0; k < NP; ++k) {
    double un = 0;
    for (int d = 0; d < DIM; ++d) un += (v[Lay::vel(k, d)] - g.wall_velocity[d]) * g.normal[d];
    for (int d = 0; d < DIM; ++d) v[Lay::vel(k, d)] -= factor * un * g.normal[d];
    if (g.has_wall_pressure && std::isfinite(g.wall_pressure[k])) {
      const double pinf = eos[k].pinf, pip = v[Lay::pres(k)] + pinf;
      const double pg = std::clamp(pip - factor * (pip - (g.wall_pressure[k] + pinf)), 0.5 * pip, 2.0 * pip);
      v[Lay::rho(k)] *= std::pow(pg / pip, 1.0 / eos[k].gamma);
      v[Lay::pres(k)] = pg - pinf;
    }
  }
  return true;
}

template <int DIM, int NP>
void fill_ghost_cells(const EmbeddedState& e, FieldArray& W, const eos::StiffenedGas* eos) {
  using Lay = Layout<DIM, NP>;
  double v[Lay::kPrim];
  for (const GhostRecord& g : e.ghosts)  // no flow cell near the image point: keep the last state
    if (ghost_state<DIM, NP>(g, W, eos, v))
      for (int q = 0; q < W.vars; ++q) W.var(q)[g.cell] = v[q];
}

// The side ghosts of thin bodies (EmbeddedState::side_ghosts), kPrim values each, per direction, into `out`.
template <int DIM, int NP>
void fill_side_ghosts(const EmbeddedState& e, const FieldArray& W, const eos::StiffenedGas* eos,
                      std::array<std::vector<double>, 3>& out) {
  using Lay = Layout<DIM, NP>;
  for (int D = 0; D < DIM; ++D) {
    const auto& sg = e.side_ghosts[D];
    out[D].resize(sg.size() * Lay::kPrim);
    for (std::size_t i = 0; i < sg.size(); ++i) {
      double* v = out[D].data() + i * Lay::kPrim;
      if (!ghost_state<DIM, NP>(sg[i].ghost, W, eos, v))
        for (int q = 0; q < W.vars; ++q) v[q] = W.var(q)[sg[i].ghost.cell];
    }
  }
}

}  // namespace cosim::fluid
