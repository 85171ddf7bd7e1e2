// Point lattices of the padded grid (cell centres and cell nodes, i fastest) and the local search
// that finds the lattice points near a face without touching the rest of the grid.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

#include "fluid_solver/core/grid.h"
#include "fluid_solver/embedded/vec.h"

namespace cosim::fluid::embedded {

template <int DIM>
struct Lattice {
  std::array<int, 3> count{1, 1, 1};
  std::array<double, 3> lower{0, 0, 0}, dx{1, 1, 1};
  std::array<double, 3> shift{0, 0, 0};  // coordinate(d, I) = lower + ((I + first) + shift) dx
  // The lattice of a block: its point I is point I + first of the whole mesh's lattice, which has `whole` points
  // per direction. Coordinates and index ranges are computed in the whole lattice's numbering, so a point has the
  // same coordinates and the same neighbours bit for bit whatever block holds it.
  std::array<int, 3> first{0, 0, 0};
  std::array<int, 3> whole{1, 1, 1};
  std::size_t size = 1;

  double coord(int d, int I) const {
    const auto ud = static_cast<std::size_t>(d);
    return d < DIM ? lower[ud] + (static_cast<double>(I + first[ud]) + shift[ud]) * dx[ud] : 0.0;
  }
  // The coordinate of the whole lattice's point 0 along d.
  double origin(int d) const { return coord(d, -first[static_cast<std::size_t>(d)]); }
  Vec3 point(int I, int J, int K) const { return {coord(0, I), coord(1, J), coord(2, K)}; }
  std::size_t index(int I, int J, int K) const {
    return static_cast<std::size_t>(I) +
           static_cast<std::size_t>(count[0]) *
               (static_cast<std::size_t>(J) + static_cast<std::size_t>(count[1]) * static_cast<std::size_t>(K));
  }
  std::array<int, 3> ijk(std::size_t idx) const {
    const auto c0 = static_cast<std::size_t>(count[0]), c1 = static_cast<std::size_t>(count[1]);
    return {static_cast<int>(idx % c0), static_cast<int>((idx / c0) % c1), static_cast<int>(idx / (c0 * c1))};
  }
  bool inside(int I, int J, int K) const {
    return I >= 0 && J >= 0 && K >= 0 && I < count[0] && J < count[1] && K < count[2];
  }
};

// Cell centres of the padded grid: lattice index == Grid::index (I = i + NG), coordinate == Grid::center.
template <int DIM>
Lattice<DIM> centre_lattice(const Grid<DIM>& g) {
  Lattice<DIM> L;
  for (std::size_t d = 0; d < 3; ++d) {
    L.count[d] = g.padded[d];
    L.lower[d] = g.lower[d];
    L.dx[d] = g.dx[d];
    L.shift[d] = static_cast<int>(d) < DIM ? 0.5 - Grid<DIM>::NG : 0.0;
    L.first[d] = g.first[d];
    L.whole[d] = static_cast<int>(d) < DIM ? g.mesh[d] + 2 * Grid<DIM>::NG : 1;
  }
  L.size = g.total;
  return L;
}

// Cell nodes (corners) of the padded grid: node (I,J,K) is the lower corner of padded cell (I,J,K).
template <int DIM>
Lattice<DIM> node_lattice(const Grid<DIM>& g) {
  Lattice<DIM> L;
  L.size = 1;
  for (std::size_t d = 0; d < 3; ++d) {
    const bool active = static_cast<int>(d) < DIM;
    L.count[d] = active ? g.padded[d] + 1 : 1;
    L.lower[d] = g.lower[d];
    L.dx[d] = g.dx[d];
    L.shift[d] = active ? -static_cast<double>(Grid<DIM>::NG) : 0.0;
    L.first[d] = g.first[d];
    L.whole[d] = active ? g.mesh[d] + 2 * Grid<DIM>::NG + 1 : 1;
    L.size *= static_cast<std::size_t>(L.count[d]);
  }
  return L;
}

// Visits every lattice point p inside the box [lo - e, hi + e] with |n.p - c| <= r, i.e. the
// points of the slab of half-width r around the face's plane n.x = c, restricted to the face's
// bounding box grown by e. Rows run along the axis where |n| is largest, so each row holds at most
// 2 r / (|n|_max dx) + 1 points and the visits per face are proportional to the cells near the
// face, not to the volume of its bounding box (a long diagonal face costs O(L/dx), not O((L/dx)^DIM)).
// `tri` (3D, optional): the face is that triangle, and each row of the two other axes is limited to the part of
// the box where the triangle grown by e lies (its extent along the row over the rows within e), instead of the
// whole grown bounding box: half the visits for the triangles of a split quad.
template <int DIM, class Visit>
void for_each_in_slab(const Lattice<DIM>& L, const Vec3& lo, const Vec3& hi, const Vec3& e, const Vec3& n, double c,
                      double r, Visit&& visit, const std::array<Vec3, 3>* tri = nullptr) {
  int a = 0;
  for (int d = 1; d < DIM; ++d)
    if (std::abs(n[static_cast<std::size_t>(d)]) > std::abs(n[static_cast<std::size_t>(a)])) a = d;
  const auto ua = static_cast<std::size_t>(a);
  if (n[ua] == 0) return;
  auto to_int = [](double v) { return static_cast<int>(std::clamp(v, -1e9, 1e9)); };
  std::array<int, 3> rmin{0, 0, 0}, rmax{0, 0, 0};
  // Ranges in the whole lattice's numbering (from its origin), then shifted to this lattice's.
  for (std::size_t d = 0; d < static_cast<std::size_t>(DIM); ++d) {
    const double origin = L.origin(static_cast<int>(d));
    rmin[d] = std::max(0, to_int(std::ceil((lo[d] - e[d] - origin) / L.dx[d])) - L.first[d]);
    rmax[d] = std::min(L.count[d] - 1, to_int(std::floor((hi[d] + e[d] - origin) / L.dx[d])) - L.first[d]);
    if (rmin[d] > rmax[d]) return;
  }
  const int b1 = (a + 1) % 3, b2 = (a + 2) % 3;  // the two other axes (inactive ones have range [0,0])
  const auto ub1 = static_cast<std::size_t>(b1), ub2 = static_cast<std::size_t>(b2);
  const double origin_a = L.origin(a);
  std::array<int, 3> I{0, 0, 0};
  for (I[ub2] = rmin[ub2]; I[ub2] <= rmax[ub2]; ++I[ub2]) {
    int r1min = rmin[ub1], r1max = rmax[ub1];
    if (DIM == 3 && tri) {
      // The triangle's extent along b1 over b2 in [z - e, z + e]: its vertices there and where its edges cross
      // the two ends (the part of a convex polygon in a strip is convex, with those points as its corners).
      const double z = L.coord(b2, I[ub2]), za = z - e[ub2], zb = z + e[ub2];
      double y0 = 1e300, y1 = -1e300;
      for (int k = 0; k < 3; ++k) {
        const Vec3& p = (*tri)[static_cast<std::size_t>(k)];
        const Vec3& q = (*tri)[static_cast<std::size_t>((k + 1) % 3)];
        if (p[ub2] >= za && p[ub2] <= zb) {
          y0 = std::min(y0, p[ub1]);
          y1 = std::max(y1, p[ub1]);
        }
        for (const double zz : {za, zb})
          if ((p[ub2] - zz) * (q[ub2] - zz) < 0) {
            const double y = p[ub1] + (zz - p[ub2]) / (q[ub2] - p[ub2]) * (q[ub1] - p[ub1]);
            y0 = std::min(y0, y);
            y1 = std::max(y1, y);
          }
      }
      if (y0 > y1) continue;
      const double origin1 = L.origin(b1);
      r1min = std::max(r1min, to_int(std::ceil((y0 - e[ub1] - origin1) / L.dx[ub1])) - L.first[ub1]);
      r1max = std::min(r1max, to_int(std::floor((y1 + e[ub1] - origin1) / L.dx[ub1])) - L.first[ub1]);
    }
    for (I[ub1] = r1min; I[ub1] <= r1max; ++I[ub1]) {
      const double s = n[ub1] * L.coord(b1, I[ub1]) + n[ub2] * L.coord(b2, I[ub2]);
      double t0 = (c - s - r) / n[ua], t1 = (c - s + r) / n[ua];
      if (t0 > t1) std::swap(t0, t1);
      const int ia = std::max(rmin[ua], to_int(std::ceil((t0 - origin_a) / L.dx[ua])) - L.first[ua]);
      const int ib = std::min(rmax[ua], to_int(std::floor((t1 - origin_a) / L.dx[ua])) - L.first[ua]);
      for (I[ua] = ia; I[ua] <= ib; ++I[ua]) visit(I[0], I[1], I[2]);
    }
  }
}

}  // namespace cosim::fluid::embedded
