// Body faces that lie on a non-periodic boundary plane of the domain (a piston filling a channel: its side
// faces on the channel walls), and how the geometry treats them: no interface segments (clip.h), and
// they are the closest face only of points on or beyond their plane (signed_distance.h).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include "fluid_solver/core/grid.h"
#include "fluid_solver/embedded/surface.h"

namespace cosim::fluid::embedded {

// Faces in a boundary plane of the domain (domain_wall_faces() below): code 0 for an ordinary face,
// 1 + 2 d + side for a face on the lower (side 0) or upper (side 1) boundary of axis d.
struct DomainWallFaces {
  std::vector<signed char> code;
  std::array<double, 3> lower{0, 0, 0}, upper{0, 0, 0}, tol{0, 0, 0};
  bool skips(std::size_t f) const { return !code.empty() && code[f] != 0; }
  // Whether face f may be the closest face of point x: ordinary faces always, wall faces only on or beyond
  // their plane.
  bool reaches(std::size_t f, const Vec3& x) const {
    if (code.empty() || code[f] == 0) return true;
    const auto d = static_cast<std::size_t>((code[f] - 1) / 2);
    return (code[f] - 1) % 2 == 0 ? x[d] <= lower[d] + tol[d] : x[d] >= upper[d] - tol[d];
  }
};

// Faces of s that lie in a non-periodic boundary plane of the domain with their normal pointing out of it
// (a piston filling a channel: its side faces on the channel walls). They give no interface segments and
// reach only the lattice points on or beyond their plane (the ghost layers outside the domain): inside the
// domain they would capture the ghost cells in the corner rows of the faces that do touch the fluid (a ghost as
// close to the side face on the wall as to the end face was mirrored about the wall instead of the moving end
// face: piston_2d at 40 x 8 was 2.5% off the reference, with the side faces outside the channel 0.1%).
template <int DIM>
DomainWallFaces domain_wall_faces(const Grid<DIM>& g, const Surface& s, const SurfaceTopology& topo,
                                  const std::array<bool, 3>& periodic) {
  DomainWallFaces w;
  w.code.assign(s.faces.size(), 0);
  for (std::size_t d = 0; d < 3; ++d) {
    w.lower[d] = g.lower[d];
    w.upper[d] = g.lower[d] + g.mesh[d] * g.dx[d];  // the whole mesh's, also on a block
    w.tol[d] = 1e-10 * g.dx[d];
  }
  const int nv = DIM == 1 ? 1 : DIM;
  for (std::size_t f = 0; f < s.faces.size(); ++f)
    for (std::size_t d = 0; d < static_cast<std::size_t>(DIM) && !w.code[f]; ++d) {
      if (periodic[d]) continue;
      const double nd = topo.face_normal[f][d];
      bool on_lo = nd < -0.5;
      bool on_hi = nd > 0.5;
      for (int k = 0; k < nv; ++k) {
        const double x = s.vertices[static_cast<std::size_t>(s.faces[f][static_cast<std::size_t>(k)])][d];
        on_lo = on_lo && std::abs(x - w.lower[d]) <= w.tol[d];
        on_hi = on_hi && std::abs(x - w.upper[d]) <= w.tol[d];
      }
      if (on_lo || on_hi) w.code[f] = static_cast<signed char>(1 + 2 * d + (on_hi ? 1 : 0));
    }
  return w;
}

}  // namespace cosim::fluid::embedded
