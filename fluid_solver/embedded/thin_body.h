// Thin bodies (numerics.md 5.7): a body thinner than about two cells has ghost cells that the
// solver reads from both sides, and a single ghost value cannot serve both. Not supported: such
// places are detected and reported (std::runtime_error naming the location), never silently used.
// "Opposite" below means unit normals with n1.n2 < opposite_cos (default -0.9, ~154 degrees).
//   T1  a flow cell F reads a ghost or solid-cut cell C (k = 1..reach cells along a grid line)
//       whose wall faces the opposite way (n_C opposite to n_F): C's value is mirrored about the
//       other side of the body. Default reach 1, the first ghost layer (the cell across the
//       fluid/solid face, whose state the face treatment of paper steps 5-6 uses);
//   T2  two adjacent flow cells whose closest walls both lie between them and are opposite (a
//       body thinner than one cell passing between two cell centres: flux would leak through it);
//   T0  one cell owns interface pieces with opposite normals (the surface folds inside one cell).
// Consequence (reach 1): a flat plate one cell thick or thinner is always refused, one between 1
// and 2 cells depending on its offset to the grid, one of 2 cells or more never (except with both
// walls exactly through cell centres, which are then flow cells by the zero convention, leaving a
// single solid row). Bodies 2-4 cells
// thick share their SECOND ghost layer between the two sides (e.g. the paper's 9.2 advection box,
// 3.25 cells on 13x13); reach 2 would refuse those, so it is an option, not the default.
// Wedge tips sharper than ~26 degrees are refused (their tip cells are shared by both faces).
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "fluid_solver/embedded/clip.h"
#include "fluid_solver/embedded/signed_distance.h"

namespace cosim::fluid::embedded {

struct ThinSpot {
  std::array<int, 3> ijk{0, 0, 0};  // interior-numbered cell
  Vec3 x{0, 0, 0};                  // its centre
  Vec3 n1{0, 0, 0}, n2{0, 0, 0};    // the two opposite normals
  std::string rule;                 // "T0", "T1", "T2"
};

template <int DIM>
std::vector<ThinSpot> find_thin_spots(const LevelSet<DIM>& centres, const std::vector<InterfaceSegment>& segments,
                                      double opposite_cos, int reach = 1) {
  std::vector<ThinSpot> spots;
  const Lattice<DIM>& C = centres.lattice;
  auto record = [&](std::size_t idx, const Vec3& n1, const Vec3& n2, const char* rule) {
    const auto I = C.ijk(idx);
    spots.push_back(ThinSpot{{I[0] - Grid<DIM>::offset(0), I[1] - Grid<DIM>::offset(1), I[2] - Grid<DIM>::offset(2)},
                             C.point(I[0], I[1], I[2]),
                             n1,
                             n2,
                             rule});
  };
  for (const auto& f : centres.band) {
    if (centres.phi[f.index] < 0) continue;  // F: a flow centre
    const auto I = C.ijk(f.index);
    for (int d = 0; d < DIM; ++d)
      for (int dir = -1; dir <= 1; dir += 2)
        for (int k = 1; k <= reach; ++k) {
          std::array<int, 3> J = I;
          J[static_cast<std::size_t>(d)] += dir * k;
          if (!C.inside(J[0], J[1], J[2])) break;
          const std::size_t cidx = C.index(J[0], J[1], J[2]);
          const BandPoint* c = centres.at(cidx);
          if (!c) break;
          if (centres.phi[cidx] < 0) {
            if (dot(c->normal, f.normal) < opposite_cos) record(cidx, f.normal, c->normal, "T1");
          } else if (k == 1) {
            const double along_f = dir * f.normal[static_cast<std::size_t>(d)],
                         along_c = dir * c->normal[static_cast<std::size_t>(d)];
            if (dot(c->normal, f.normal) < opposite_cos && along_f < 0 && along_c > 0)
              record(f.index, f.normal, c->normal, "T2");
            break;  // a flow neighbour: the solver reads past it only through another flow cell
          } else {
            break;
          }
        }
  }
  for (std::size_t a = 0; a < segments.size();) {
    std::size_t e = a;
    while (e < segments.size() && segments[e].cell == segments[a].cell) ++e;
    for (std::size_t p = a; p < e; ++p)
      for (std::size_t q = p + 1; q < e; ++q)
        if (dot(segments[p].normal, segments[q].normal) < opposite_cos) {
          record(segments[p].cell, segments[p].normal, segments[q].normal, "T0");
          p = q = e;  // one report per cell
        }
    a = e;
  }
  return spots;
}

inline std::string describe_thin_spot(const ThinSpot& t) {
  std::ostringstream m;
  m << "embedded geometry: body thinner than two cells near x = (" << t.x[0] << ", " << t.x[1] << ", " << t.x[2]
    << "), cell (" << t.ijk[0] << ", " << t.ijk[1] << ", " << t.ijk[2] << "), rule " << t.rule
    << ": walls with opposite normals (" << t.n1[0] << ", " << t.n1[1] << ", " << t.n1[2] << ") and (" << t.n2[0]
    << ", " << t.n2[1] << ", " << t.n2[2]
    << ") share its ghost cells; thin bodies need two-sided ghost states, which are not supported: refine the grid or "
       "thicken the body";
  return m.str();
}

}  // namespace cosim::fluid::embedded
