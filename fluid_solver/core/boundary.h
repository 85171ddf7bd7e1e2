// Ghost cells of the primitive arrays from the boundary conditions of each side. The directions are
// filled one after the other, each over the ghost layers of the directions filled before it, so the
// edge and corner ghosts hold valid states too: the flux stencils never read them, but the embedded
// boundary's image-point and sampling stencils do where a body crosses the domain boundary (they read
// zeros there before: a zero pressure in 3D image points).
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

  void fill(FieldArray& W) const {
    for (int d = 0; d < DIM; ++d)
      for (int side = 0; side < 2; ++side) fill_side(W, d, side);
  }

 private:
  void fill_side(FieldArray& W, int d, int side) const {
    const int n = g_.n[d];
    const int e1 = (d + 1) % 3, e2 = (d + 2) % 3;  // the two other axes
    // An axis filled before this one (e < d, active) is swept over its ghost layers as well.
    const int g1 = e1 < d && e1 < DIM ? Grid<DIM>::NG : 0, g2 = e2 < d && e2 < DIM ? Grid<DIM>::NG : 0;
    const BoundaryKind kind = kind_[d][side];
    for (int b = -g2; b < g_.n[e2] + g2; ++b)
      for (int a = -g1; a < g_.n[e1] + g1; ++a)
        for (int layer = 1; layer <= Grid<DIM>::NG; ++layer) {
          const int ghost = side == 0 ? -layer : n - 1 + layer;
          int src = 0;
          switch (kind) {
            case BoundaryKind::Transmissive: src = side == 0 ? 0 : n - 1; break;
            case BoundaryKind::Wall: src = side == 0 ? layer - 1 : n - layer; break;
            case BoundaryKind::Periodic: src = side == 0 ? n - layer : layer - 1; break;
            case BoundaryKind::Inflow: src = 0; break;
          }
          const std::size_t cg = at(d, ghost, e1, a, e2, b), cs = at(d, src, e1, a, e2, b);
          if (kind == BoundaryKind::Inflow) {
            for (int v = 0; v < W.vars; ++v) W.var(v)[cg] = inflow_[d][side][v];
            continue;
          }
          for (int v = 0; v < W.vars; ++v) W.var(v)[cg] = W.var(v)[cs];
          if (kind == BoundaryKind::Wall)
            for (int k = 0; k < NP; ++k) W.var(Lay::vel(k, d))[cg] = -W.var(Lay::vel(k, d))[cs];
        }
  }

  std::size_t at(int d, int id, int e1, int ia, int e2, int ib) const {
    int ijk[3];
    ijk[d] = id;
    ijk[e1] = ia;
    ijk[e2] = ib;
    return g_.index(ijk[0], ijk[1], ijk[2]);
  }

  Grid<DIM> g_;
  std::array<std::array<BoundaryKind, 2>, 3> kind_{};
  std::array<std::array<std::vector<double>, 2>, 3> inflow_{};
};

}  // namespace cosim::fluid
