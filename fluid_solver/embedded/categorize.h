// Cell categories of paper section 6, Table 1, from phi_C (centre) and phi_N (nodes):
//   fluid      phi_C >= 0, no phi_N < 0
//   fluid-cut  phi_C >= 0, some phi_N < 0
//   solid-cut  phi_C <  0, some phi_N > 0   (the paper's "some phi_N < 0" read as: the cut cell
//                                            whose centre is in the solid)
//   ghost      phi_C <  0, no phi_N > 0, and a flow (fluid / fluid-cut) cell within
//              `ghost_layers` cells along a grid line (the MUSCL reach of the solver, whose
//              stencils are one-dimensional per direction; diagonal neighbours are never read)
//   solid      the rest of the body (no work).
// Zero convention: a centre with phi_C = 0 is a flow cell ("the surface belongs to the fluid");
// a node with phi_N = 0 cuts nothing by itself (a cell is cut only by a strict sign change), where zero
// means |phi_N| <= 1e-10 dx, the tolerance of clip.h: a wall on a grid line up to round-off (0.3 against
// 6 x 0.05) touches the nodes of the line and cuts the cells on its solid side only.
// Cells owning an interface piece without a strict sign change are promoted to fluid-cut /
// solid-cut by the side of their centre: a body vertex poking into a cell between its nodes, and
// a wall lying exactly on a grid line, whose pieces belong to the cells on its solid side
// (clip.h). So the cut cells are exactly the cells that own interface segments, and a node that
// only touches the surface makes no cut cell.
// Work: the band cells only; everything outside the band was set by the level-set row fill.
#pragma once

#include <algorithm>
#include <array>
#include <vector>

#include "fluid_solver/core/embedded_state.h"
#include "fluid_solver/embedded/clip.h"
#include "fluid_solver/embedded/signed_distance.h"

namespace cosim::fluid::embedded {

struct CategoryCounts {
  std::size_t fluid_cut = 0, solid_cut = 0, ghost = 0;
  std::size_t promoted = 0;  // cut cells found by their segments only (no strict sign change at the nodes)
};

template <int DIM>
CategoryCounts categorize(const LevelSet<DIM>& centres, const LevelSet<DIM>& nodes,
                          const std::vector<InterfaceSegment>& segments, int ghost_layers,
                          std::vector<std::uint8_t>& category) {
  constexpr auto kFluid = static_cast<std::uint8_t>(CellKind::Fluid),
                 kFluidCut = static_cast<std::uint8_t>(CellKind::FluidCut),
                 kSolidCut = static_cast<std::uint8_t>(CellKind::SolidCut),
                 kGhost = static_cast<std::uint8_t>(CellKind::Ghost),
                 kSolid = static_cast<std::uint8_t>(CellKind::Solid);
  CategoryCounts counts;
  const Lattice<DIM>& C = centres.lattice;
  const Lattice<DIM>& N = nodes.lattice;
  double zero = C.dx[0];
  for (std::size_t d = 1; d < static_cast<std::size_t>(DIM); ++d) zero = std::min(zero, C.dx[d]);
  zero *= 1e-10;
  for (const auto& b : centres.band) {
    const auto I = C.ijk(b.index);
    bool some_fluid_node = false, some_solid_node = false;  // strictly > 0 / < 0
    for (int c = 0; c < (DIM > 2 ? 2 : 1); ++c)
      for (int bb = 0; bb < (DIM > 1 ? 2 : 1); ++bb)
        for (int a = 0; a < 2; ++a) {
          const double pn = nodes.phi[N.index(I[0] + a, I[1] + bb, I[2] + c)];
          some_solid_node = some_solid_node || pn < -zero;
          some_fluid_node = some_fluid_node || pn > zero;
        }
    if (centres.phi[b.index] >= 0) category[b.index] = some_solid_node ? kFluidCut : kFluid;
    else category[b.index] = some_fluid_node ? kSolidCut : kSolid;
  }
  for (const auto& seg : segments) {
    std::uint8_t& k = category[seg.cell];
    if (k == kFluid) k = kFluidCut, ++counts.promoted;
    else if (k == kSolid) k = kSolidCut, ++counts.promoted;
  }
  // Ghost cells: a solid centre within ghost_layers cells of a flow centre along a grid line (the
  // solver's stencils are one-dimensional per direction) is closer than ghost_layers * dx_max to the
  // surface, so only band cells with |phi| below that are candidates.
  double hmax = 0;
  for (std::size_t d = 0; d < static_cast<std::size_t>(DIM); ++d) hmax = std::max(hmax, C.dx[d]);
  const double reach = ghost_layers * hmax * (1 + 1e-12);
  for (const auto& b : centres.band) {
    if (category[b.index] != kSolid || -centres.phi[b.index] > reach) continue;
    const auto I = C.ijk(b.index);
    bool near_flow = false;
    for (int d = 0; d < DIM && !near_flow; ++d)
      for (int step = -ghost_layers; step <= ghost_layers; ++step) {
        std::array<int, 3> J = I;
        J[static_cast<std::size_t>(d)] += step;
        if (step == 0 || !C.inside(J[0], J[1], J[2])) continue;
        if (centres.phi[C.index(J[0], J[1], J[2])] >= 0) {
          near_flow = true;
          break;
        }
      }
    if (near_flow) category[b.index] = kGhost;
  }
  for (const auto& b : centres.band) {
    const std::uint8_t k = category[b.index];
    counts.fluid_cut += k == kFluidCut;
    counts.solid_cut += k == kSolidCut;
    counts.ghost += k == kGhost;
  }
  return counts;
}

}  // namespace cosim::fluid::embedded
