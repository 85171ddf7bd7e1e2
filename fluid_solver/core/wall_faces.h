// The grid faces between a flow cell and a ghost/solid-cut cell, per direction (paper Fig. 4,
// steps 5-6), from the cell categories, the signed distance at cell centres and the ghost records.
#pragma once

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include "fluid_solver/core/embedded_state.h"
#include "fluid_solver/core/grid.h"

namespace cosim::fluid {

// Cells 2, 3 and 4 of wall face f along D, counted from its flow cell away from the wall (cell 1): each the next
// flow cell of the padded row, or the one before it where there is none.
template <int DIM>
void set_cells_away(const Grid<DIM>& g, const EmbeddedState& e, int D, WallFace& f) {
  const std::ptrdiff_t s = g.stride[D];
  const std::ptrdiff_t step = f.solid_on_high_side ? -s : s;
  std::ptrdiff_t pos = static_cast<std::ptrdiff_t>(f.fluid_cell) / s % g.padded[D];  // along D in the padded row
  std::size_t* away[3] = {&f.fluid_cell2, &f.fluid_cell3, &f.fluid_cell4};
  std::size_t c = f.fluid_cell;
  for (std::size_t* a : away) {
    pos += step > 0 ? 1 : -1;
    const std::size_t n = static_cast<std::size_t>(static_cast<std::ptrdiff_t>(c) + step);
    if (pos >= 0 && pos < g.padded[D] && is_flow_cell(e.kind[n])) c = n;
    else pos = -2 * g.padded[D];  // none: the rest repeat the last flow cell
    *a = c;
  }
}

// phi: signed distance at every padded cell centre (> 0 in the fluid). The interface point I lies
// on the line between the two centres where phi changes sign (linear interpolation); d is its
// distance from the flow cell's centre in cells. The normal and wall velocity at the face are
// those of the solid cell's ghost record (its closest surface point); orient_wall_faces may then choose a better one.
template <int DIM>
void build_wall_faces(const Grid<DIM>& g, const std::vector<double>& phi, EmbeddedState& e) {
  for (int D = 0; D < DIM; ++D) {
    auto& faces = e.faces[D];
    faces.clear();
    const std::size_t s = static_cast<std::size_t>(g.stride[D]);
    for (const GhostRecord& gr : e.ghosts) {
      const std::size_t c = gr.cell;
      for (int side = 0; side < 2; ++side) {  // neighbour below (0) or above (1) along D
        const std::size_t n = side == 0 ? c - s : c + s;
        if (n >= g.total || !is_flow_cell(e.kind[n])) continue;
        WallFace f;
        f.solid_cell = c;
        f.fluid_cell = n;
        f.solid_on_high_side = side == 0;
        set_cells_away<DIM>(g, e, D, f);
        f.normal = gr.normal;
        f.wall_velocity = gr.wall_velocity;
        f.wall = gr.wall;
        const double pf = phi[n], ps = phi[c];
        f.d = pf - ps > 0 ? std::min(1.0, std::max(0.0, pf / (pf - ps))) : 0.5;
        faces.push_back(f);
      }
    }
  }
}

// The wall a grid face crosses: the ghost's closest point may lie on another face of the body than the one the
// grid line F -> G passes through (near an edge or a corner of a box its normal can be perpendicular to the line,
// and a mirror about it leaves the velocity through the grid face unchanged: mass leaks through the wall). Of the
// ghost's wall and the flow cell's own wall (its closest surface point: `flow_wall(F, normal)` returns false when
// there is none), the one whose normal lies closest to the line is used (the flow cell's: its wall source is
// `flow_source(F)`, whose velocity set_wall_values sets), and where neither has |n_D| >= 0.2 (a normal nearly
// perpendicular to the line: a corner) the face is mirrored about the grid face.
template <int DIM, class FlowWall, class FlowSource>
void orient_wall_faces(EmbeddedState& e, const FlowWall& flow_wall, const FlowSource& flow_source) {
  for (int D = 0; D < DIM; ++D)
    for (WallFace& f : e.faces[D]) {
      std::array<double, 3> n{0, 0, 0};
      const double towards = f.solid_on_high_side ? -1.0 : 1.0;  // n_D of a wall facing the flow cell along D
      if (flow_wall(f.fluid_cell, n) && towards * n[D] > towards * f.normal[D]) {
        f.normal = n;
        f.wall = flow_source(f.fluid_cell);
      }
      if (towards * f.normal[D] < 0.2) {
        f.normal = {0, 0, 0};
        f.normal[D] = towards;
      }
    }
}

// Thin bodies (EmbeddedState::side_ghosts, fluid_solver/embedded/thin_body.h): a wall face whose solid cell's
// record serves the other side of the body takes the flow cell's own wall (normal, velocity, distance), and a
// pair of side ghosts across a face between two flow cells makes that face a BlockedFace.
template <int DIM>
void build_thin_body_faces(const Grid<DIM>& g, EmbeddedState& e) {
  for (int D = 0; D < DIM; ++D) {
    const auto& sgs = e.side_ghosts[D];
    e.blocked[D].clear();
    if (sgs.empty()) continue;
    const auto find = [&](std::size_t flow_cell, bool across_high) -> const SideGhost* {
      auto it = std::lower_bound(sgs.begin(), sgs.end(), std::make_pair(flow_cell, across_high),
                                 [](const SideGhost& a, const std::pair<std::size_t, bool>& k) {
                                   return a.flow_cell != k.first ? a.flow_cell < k.first : a.across_high < k.second;
                                 });
      return it != sgs.end() && it->flow_cell == flow_cell && it->across_high == across_high ? &*it : nullptr;
    };
    const auto side_face = [&](const SideGhost& sg) {
      WallFace f;
      f.fluid_cell = sg.flow_cell;
      f.solid_cell = sg.ghost.cell;
      f.solid_on_high_side = sg.across_high;
      set_cells_away<DIM>(g, e, D, f);
      f.normal = sg.ghost.normal;
      f.wall_velocity = sg.ghost.wall_velocity;
      f.wall = sg.ghost.wall;
      f.d = sg.face_distance;
      return f;
    };
    for (WallFace& wf : e.faces[D])
      if (const SideGhost* sg = find(wf.fluid_cell, wf.solid_on_high_side); sg && !sg->blocked) wf = side_face(*sg);
    for (const SideGhost& sg : sgs) {
      if (!sg.blocked || !sg.across_high) continue;
      const SideGhost* other = find(sg.ghost.cell, false);
      if (!other || !other->blocked || other->ghost.cell != sg.flow_cell)
        throw std::logic_error("embedded geometry: a blocked face seen from one side only");
      e.blocked[D].push_back(BlockedFace{side_face(sg), side_face(*other)});
    }
  }
}

}  // namespace cosim::fluid
