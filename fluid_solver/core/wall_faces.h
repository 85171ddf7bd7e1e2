// The grid faces between a flow cell and a ghost/solid-cut cell, per direction (paper Fig. 4,
// steps 5-6), from the cell categories, the signed distance at cell centres and the ghost records.
#pragma once

#include <algorithm>
#include <cmath>
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

}  // namespace cosim::fluid
