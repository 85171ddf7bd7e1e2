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

// phi: signed distance at every padded cell centre (> 0 in the fluid). The interface point I lies
// on the line between the two centres where phi changes sign (linear interpolation); d is its
// distance from the flow cell's centre in cells. The normal and wall velocity at the face are
// those of the solid cell's ghost record (its closest surface point), except for a solid centre on the
// surface itself (below).
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
        const std::size_t n2 = side == 0 ? n - s : n + s;
        f.fluid_cell2 = n2 < g.total && is_flow_cell(e.kind[n2]) ? n2 : n;
        f.solid_on_high_side = side == 0;
        f.normal = gr.normal;
        // A solid cell whose centre lies on the surface (up to 1e-3 dx) at a corner of the body, e.g. a clamped
        // corner node on the cell centre, gets the normal of one of the faces meeting there; across a grid face
        // nearly parallel to that normal (|n_D| < 0.45) the mirror would leave the velocity through the face
        // unchanged and let mass through the wall. Such a face is mirrored about the grid face instead.
        if (gr.distance < 1e-3 * g.dx[D] && std::abs(gr.normal[D]) < 0.45) {
          f.normal = {0, 0, 0};
          f.normal[D] = side == 0 ? -1.0 : 1.0;  // from the solid cell towards the flow cell
        }
        f.wall_velocity = gr.wall_velocity;
        const double pf = phi[n], ps = phi[c];
        f.d = pf - ps > 0 ? std::min(1.0, std::max(0.0, pf / (pf - ps))) : 0.5;
        faces.push_back(f);
      }
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
    const std::size_t s = static_cast<std::size_t>(g.stride[D]);
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
      const std::size_t away = sg.across_high ? sg.flow_cell - s : sg.flow_cell + s;
      f.fluid_cell2 = away < g.total && is_flow_cell(e.kind[away]) ? away : sg.flow_cell;
      f.normal = sg.ghost.normal;
      f.wall_velocity = sg.ghost.wall_velocity;
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
