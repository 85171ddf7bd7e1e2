// Embedded bodies on one block of a split mesh: the geometry is built over the block's cells plus a margin of the
// mesh around them (margin_grid; clipped to the mesh, whose ghost layers it then includes as the whole mesh's grid
// does), so that every cell the block's records read is cut exactly as on the whole mesh (the lattice's
// coordinates and ranges come from the whole mesh's numbering: embedded/lattice.h). The records of the block's
// padded cells are then restricted to the block's arrays (restrict_to_block): indices of its padded cells, and
// far slots (total + s) for the cells beyond, whose values come from their owners (BlockLinks::exchange_far).
#pragma once

#include <algorithm>
#include <array>
#include <vector>

#include "fluid_solver/core/embedded_state.h"
#include "fluid_solver/core/grid.h"
#include "fluid_solver/embedded/image_points.h"
#include "fluid_solver/embedded/reach.h"

namespace cosim::fluid {

// The block's cells plus embedded::margin_cells of the mesh on every side, clipped to the mesh.
template <int DIM>
Grid<DIM> margin_grid(const Grid<DIM>& block) {
  std::array<int, 3> from = block.first, count = block.n;
  for (int d = 0; d < DIM; ++d) {
    const int m = embedded::margin_cells<DIM>(block.dx, d, Grid<DIM>::NG);
    const int lo = std::max(0, block.first[d] - m), hi = std::min(block.mesh[d], block.first[d] + block.n[d] + m);
    from[d] = lo;
    count[d] = hi - lo;
  }
  return sub_grid(block, from, count);
}

// The records wanted of the margin grid E: those of the block's padded cells (E's lattice numbering).
template <int DIM>
void want_block_records(const Grid<DIM>& E, const Grid<DIM>& block, embedded::ImagePointOptions& o) {
  for (int d = 0; d < 3; ++d) {
    o.want_lo[d] = d < DIM ? block.first[d] - E.first[d] : 0;
    o.want_hi[d] = o.want_lo[d] + block.padded[d];
  }
}

// The padded cell of `block` holding global cell g (false: not one of its padded cells).
template <int DIM>
bool block_cell(const Grid<DIM>& block, const std::array<int, 3>& g, std::size_t& p) {
  std::array<int, 3> l{0, 0, 0};
  for (int d = 0; d < DIM; ++d) {
    l[d] = g[d] - block.first[d];
    if (l[d] < -Grid<DIM>::NG || l[d] >= block.n[d] + Grid<DIM>::NG) return false;
  }
  p = block.index(l[0], l[1], l[2]);
  return true;
}

// The records of state e (built on the margin grid E) that the block uses, with the block's indices: ghost records
// and side ghosts of its padded cells, the wall and blocked faces between two of them. `far` gets the global
// indices of the cells beyond its padded cells that they read (far slot s = block.total + s), in the mesh's order.
template <int DIM>
EmbeddedState restrict_to_block(const EmbeddedState& e, const Grid<DIM>& E, const Grid<DIM>& block,
                                std::vector<std::array<int, 3>>& far) {
  const auto inside = [&](std::size_t p) {
    std::size_t q = 0;
    return block_cell(block, E.global_ijk(p), q);
  };
  std::vector<std::size_t> far_e;  // E's indices of the far cells (E's order is the mesh's)
  const auto note = [&](std::size_t p) {
    if (!inside(p)) far_e.push_back(p);
  };
  const auto keep_record = [&](const GhostRecord& r) { return inside(r.cell); };
  const auto keep_face = [&](const WallFace& f) { return inside(f.fluid_cell) && inside(f.solid_cell); };
  const auto note_record = [&](const GhostRecord& r) {
    for (int s = 0; s < r.stencil_size; ++s) note(r.stencil[static_cast<std::size_t>(s)]);
  };
  const auto note_face = [&](const WallFace& f) {
    for (std::size_t c : {f.fluid_cell2, f.fluid_cell3, f.fluid_cell4}) note(c);
  };
  for (const GhostRecord& r : e.ghosts)
    if (keep_record(r)) note_record(r);
  for (int D = 0; D < DIM; ++D) {
    for (const WallFace& f : e.faces[D])
      if (keep_face(f)) note_face(f);
    for (const SideGhost& sg : e.side_ghosts[D])
      if (inside(sg.flow_cell) && keep_record(sg.ghost)) note_record(sg.ghost);
    for (const BlockedFace& bf : e.blocked[D])
      if (keep_face(bf.low) && keep_face(bf.high)) {
        note_face(bf.low);
        note_face(bf.high);
      }
  }
  std::sort(far_e.begin(), far_e.end());
  far_e.erase(std::unique(far_e.begin(), far_e.end()), far_e.end());
  far.clear();
  for (std::size_t p : far_e) far.push_back(E.global_ijk(p));
  const auto map = [&](std::size_t p) {
    std::size_t q = 0;
    if (block_cell(block, E.global_ijk(p), q)) return q;
    return block.total + static_cast<std::size_t>(std::lower_bound(far_e.begin(), far_e.end(), p) - far_e.begin());
  };
  const auto map_record = [&](GhostRecord r) {
    r.cell = map(r.cell);
    for (int s = 0; s < r.stencil_size; ++s)
      r.stencil[static_cast<std::size_t>(s)] = map(r.stencil[static_cast<std::size_t>(s)]);
    return r;
  };
  const auto map_face = [&](WallFace f) {
    f.fluid_cell = map(f.fluid_cell);
    f.fluid_cell2 = map(f.fluid_cell2);
    f.fluid_cell3 = map(f.fluid_cell3);
    f.fluid_cell4 = map(f.fluid_cell4);
    f.solid_cell = map(f.solid_cell);
    return f;
  };
  EmbeddedState out;
  out.active = e.active;
  out.max_wall_speed = e.max_wall_speed;
  out.blocked_x = e.blocked_x;  // the margin's answer; the caller's is the whole mesh's (EmbeddedBodiesRun)
  out.far_cells = far_e.size();
  out.wall_sources = e.wall_sources;  // the records keep their sources' indices
  out.kind.resize(block.total);
  // embedded.conservative: the fluid fractions and their rates of the padded cells too (E's are the whole mesh's).
  const bool fractions = !e.fluid_fraction.empty(), rates = !e.fluid_fraction_rate.empty();
  if (fractions) out.fluid_fraction.resize(block.total);
  if (rates) out.fluid_fraction_rate.resize(block.total);
  for (std::size_t p = 0; p < block.total; ++p) {  // every padded cell of the block is a cell of E
    const std::array<int, 3> g = block.global_ijk(p);
    const std::size_t q = E.index(g[0] - E.first[0], g[1] - E.first[1], g[2] - E.first[2]);
    out.kind[p] = e.kind[q];
    if (fractions) out.fluid_fraction[p] = e.fluid_fraction[q];
    if (rates) out.fluid_fraction_rate[p] = e.fluid_fraction_rate[q];
  }
  for (const GhostRecord& r : e.ghosts)
    if (keep_record(r)) {
      out.ghosts.push_back(map_record(r));
      out.own_ghosts += block.owns(out.ghosts.back().cell) ? 1 : 0;
    }
  for (int D = 0; D < DIM; ++D) {
    for (const WallFace& f : e.faces[D])
      if (keep_face(f)) out.faces[D].push_back(map_face(f));
    for (const SideGhost& sg : e.side_ghosts[D])
      if (inside(sg.flow_cell) && keep_record(sg.ghost)) {
        SideGhost m = sg;
        m.ghost = map_record(sg.ghost);
        m.flow_cell = map(sg.flow_cell);
        out.side_ghosts[D].push_back(m);
      }
    for (const BlockedFace& bf : e.blocked[D])
      if (keep_face(bf.low) && keep_face(bf.high))
        out.blocked[D].push_back(BlockedFace{map_face(bf.low), map_face(bf.high)});
  }
  return out;
}

}  // namespace cosim::fluid
