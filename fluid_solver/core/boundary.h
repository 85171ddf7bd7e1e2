// Ghost cells of the primitive arrays from the boundary conditions of each side. The directions are
// filled one after the other (x row by row, fill_x_row; then y and z, fill), each over the ghost layers of the
// directions filled before it, so the
// edge and corner ghosts hold valid states too: the flux stencils never read them, but the embedded
// boundary's image-point and sampling stencils do where a body crosses the domain boundary (they read
// zeros there before: a zero pressure in 3D image points).
// On a block of a split mesh (MeshBlock), the sides whose ghosts a neighbouring block's cells fill are left alone:
// the exchange fills them, direction by direction in the same order (fill_direction between the exchanges).
#pragma once

#include <array>
#include <vector>

#include "fluid_solver/core/grid.h"
#include "fluid_solver/core/layout.h"
#include "fluid_solver/core/scene.h"

namespace cosim::fluid {

template <int DIM, int NP>
class BoundaryFiller {
  using Lay = Layout<DIM, NP>;

 public:
  BoundaryFiller() = default;
  BoundaryFiller(const FluidScene& scene, const Grid<DIM>& g, const eos::StiffenedGas (&eos)[NP]) : g_(g) {
    for (int d = 0; d < DIM; ++d)
      for (int side = 0; side < 2; ++side) {
        const Boundary& b = scene.boundaries[d][side];
        kind_[d][side] = b.kind;
        exchanged_[d][side] = scene.block.exchanged[d][side];
        if (b.kind != BoundaryKind::Inflow) continue;
        auto& w = inflow_[d][side];
        w.assign(Lay::kPrim, 0.0);
        for (int k = 0; k < NP; ++k) {
          const PhaseValue& v = b.inflow[k];
          w[Lay::rho(k)] = v.rho;
          for (int dd = 0; dd < DIM; ++dd) w[Lay::vel(k, dd)] = v.velocity[dd];
          w[Lay::pres(k)] = v.p;
          w[Lay::sound(k)] = eos[k].sound_speed(v.rho, v.p);
        }
        if constexpr (NP == 2) w[Lay::palpha] = b.inflow[0].alpha;
      }
  }

  // The y and z ghosts, over the x ghost layers too: call it after fill_x_row on every interior row (the pass that
  // computes the rows fills their x ghosts while they are in cache).
  void fill(FieldArray& W) const {
    for (int d = 1; d < DIM; ++d) fill_direction(W, d);
  }
  // The ghosts of the sides along d (d > 0) that a boundary condition fills.
  void fill_direction(FieldArray& W, int d) const {
    for (int side = 0; side < 2; ++side)
      if (!exchanged_[d][side]) fill_side(W, d, side);
  }
  // Whether any side's ghosts come from a neighbouring block.
  bool any_exchanged() const {
    for (const auto& e : exchanged_)
      if (e[0] || e[1]) return true;
    return false;
  }
  // The x ghosts of the interior row starting at cell `base`, every variable: fill's first direction one row at a
  // time, for a pass that has the row in cache (the primitives).
  void fill_x_row(FieldArray& W, std::size_t base) const {
    const int n = g_.n[0];
    for (int side = 0; side < 2; ++side) {
      if (exchanged_[0][side]) continue;
      const BoundaryKind kind = kind_[0][side];
      for (int layer = 1; layer <= Grid<DIM>::NG; ++layer) {
        const int ghost = side == 0 ? -layer : n - 1 + layer;
        const std::size_t g = static_cast<std::size_t>(static_cast<std::ptrdiff_t>(base) + ghost);
        const std::size_t src = base + static_cast<std::size_t>(source(kind, n, side, layer));
        for (int v = 0; v < W.vars; ++v) {
          double* w = W.var(v);
          w[g] = kind == BoundaryKind::Inflow ? inflow_[0][side][static_cast<std::size_t>(v)] : w[src];
        }
        if (kind == BoundaryKind::Wall)
          for (int k = 0; k < NP; ++k) W.var(Lay::vel(k, 0))[g] = -W.var(Lay::vel(k, 0))[src];
      }
    }
  }

 private:
  // Per variable and ghost layer, the layer's cells in memory order (x fastest): the copies stream.
  void fill_side(FieldArray& W, int d, int side) const {
    constexpr int NG = Grid<DIM>::NG;
    const int n = g_.n[d];
    // An axis filled before this one (e < d, active) is swept over its ghost layers as well.
    int lo[3], hi[3];
    for (int e = 0; e < 3; ++e) {
      const bool before = e < d && e < DIM;
      lo[e] = before ? -NG : 0;
      hi[e] = before ? g_.n[e] + NG : g_.n[e];
    }
    const BoundaryKind kind = kind_[d][side];
    for (int layer = 1; layer <= NG; ++layer) {
      const int ghost = side == 0 ? -layer : n - 1 + layer;
      const int src = source(kind, n, side, layer);
      lo[d] = ghost;
      hi[d] = ghost + 1;
      const std::ptrdiff_t shift = static_cast<std::ptrdiff_t>(src - ghost) * g_.stride[d];
      const int len = hi[0] - lo[0];
      for (int v = 0; v < W.vars; ++v) {
        double* w = W.var(v);
        bool flip = false;  // a wall mirrors the normal velocities
        for (int k = 0; k < NP; ++k) flip = flip || (kind == BoundaryKind::Wall && v == Lay::vel(k, d));
        const double value = kind == BoundaryKind::Inflow ? inflow_[d][side][static_cast<std::size_t>(v)] : 0.0;
        for (int c = lo[2]; c < hi[2]; ++c)
          for (int b = lo[1]; b < hi[1]; ++b) {
            double* row = w + g_.index(lo[0], b, c);
            if (kind == BoundaryKind::Inflow)
              for (int i = 0; i < len; ++i) row[i] = value;
            else if (flip)
              for (int i = 0; i < len; ++i) row[i] = -row[i + shift];
            else
              for (int i = 0; i < len; ++i) row[i] = row[i + shift];
          }
      }
    }
  }

  // The interior cell (index along the direction of n cells) that ghost layer `layer` of a side copies.
  static int source(BoundaryKind kind, int n, int side, int layer) {
    switch (kind) {
      case BoundaryKind::Transmissive: return side == 0 ? 0 : n - 1;
      case BoundaryKind::Wall: return side == 0 ? layer - 1 : n - layer;
      case BoundaryKind::Periodic: return side == 0 ? n - layer : layer - 1;
      case BoundaryKind::Inflow: return 0;
    }
    return 0;
  }

  Grid<DIM> g_;
  std::array<std::array<BoundaryKind, 2>, 3> kind_{};
  std::array<std::array<bool, 2>, 3> exchanged_{};
  std::array<std::array<std::vector<double>, 2>, 3> inflow_{};
};

}  // namespace cosim::fluid
