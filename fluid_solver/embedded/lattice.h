// Point lattices of the padded grid (cell centres and cell nodes, i fastest) and the local search
// that finds the lattice points near a face without touching the rest of the grid.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "fluid_solver/core/grid.h"
#include "fluid_solver/embedded/vec.h"

namespace cosim::fluid::embedded {

template <int DIM>
struct Lattice {
  std::array<int, 3> count{1, 1, 1};
  std::array<double, 3> lower{0, 0, 0}, dx{1, 1, 1};
  std::array<double, 3> shift{0, 0, 0};  // coordinate(d, I) = lower + (I + shift) dx
  std::size_t size = 1;

  double coord(int d, int I) const {
    return d < DIM ? lower[static_cast<std::size_t>(d)] +
                         (static_cast<double>(I) + shift[static_cast<std::size_t>(d)]) * dx[static_cast<std::size_t>(d)]
                   : 0.0;
  }
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
    L.size *= static_cast<std::size_t>(L.count[d]);
  }
  return L;
}

// Visits every lattice point p inside the box [lo - e, hi + e] with |n.p - c| <= r, i.e. the
// points of the slab of half-width r around the face's plane n.x = c, restricted to the face's
// bounding box grown by e. Rows run along the axis where |n| is largest, so each row holds at most
// 2 r / (|n|_max dx) + 1 points and the visits per face are proportional to the cells near the
// face, not to the volume of its bounding box (a long diagonal face costs O(L/dx), not O((L/dx)^DIM)).
template <int DIM, class Visit>
void for_each_in_slab(const Lattice<DIM>& L, const Vec3& lo, const Vec3& hi, const Vec3& e, const Vec3& n, double c,
                      double r, Visit&& visit) {
  int a = 0;
  for (int d = 1; d < DIM; ++d)
    if (std::abs(n[static_cast<std::size_t>(d)]) > std::abs(n[static_cast<std::size_t>(a)])) a = d;
  const auto ua = static_cast<std::size_t>(a);
  if (n[ua] == 0) return;
  auto to_int = [](double v) { return static_cast<int>(std::clamp(v, -1e9, 1e9)); };
  std::array<int, 3> rmin{0, 0, 0}, rmax{0, 0, 0};
  for (std::size_t d = 0; d < static_cast<std::size_t>(DIM); ++d) {
    const double origin = L.coord(static_cast<int>(d), 0);
    rmin[d] = std::max(0, to_int(std::ceil((lo[d] - e[d] - origin) / L.dx[d])));
    rmax[d] = std::min(L.count[d] - 1, to_int(std::floor((hi[d] + e[d] - origin) / L.dx[d])));
    if (rmin[d] > rmax[d]) return;
  }
  const int b1 = (a + 1) % 3, b2 = (a + 2) % 3;  // the two other axes (inactive ones have range [0,0])
  const auto ub1 = static_cast<std::size_t>(b1), ub2 = static_cast<std::size_t>(b2);
  const double origin_a = L.coord(a, 0);
  std::array<int, 3> I{0, 0, 0};
  for (I[ub2] = rmin[ub2]; I[ub2] <= rmax[ub2]; ++I[ub2]) {
    for (I[ub1] = rmin[ub1]; I[ub1] <= rmax[ub1]; ++I[ub1]) {
      const double s = n[ub1] * L.coord(b1, I[ub1]) + n[ub2] * L.coord(b2, I[ub2]);
      double t0 = (c - s - r) / n[ua], t1 = (c - s + r) / n[ua];
      if (t0 > t1) std::swap(t0, t1);
      const int ia = std::max(rmin[ua], to_int(std::ceil((t0 - origin_a) / L.dx[ua])));
      const int ib = std::min(rmax[ua], to_int(std::floor((t1 - origin_a) / L.dx[ua])));
      for (I[ua] = ia; I[ua] <= ib; ++I[ua]) visit(I[0], I[1], I[2]);
    }
  }
}

}  // namespace cosim::fluid::embedded
