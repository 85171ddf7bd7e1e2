// Uniform Cartesian grid with NG ghost layers on each side of every active direction.
// Cells are stored with i (x) fastest; inactive directions have size 1 and no ghosts.
// The grid may be one block of a larger mesh (a rank's part under MPI): `first` is the global index of its cell 0
// along each axis, and positions come from the global mesh (origin and spacing of the whole mesh, global index), so
// a cell has the same coordinates bit for bit whatever block holds it.
#pragma once

#include <array>
#include <cstddef>

namespace cosim::fluid {

template <int DIM>
struct Grid {
  static constexpr int NG = 2;         // MUSCL needs two ghost layers
  std::array<int, 3> n{1, 1, 1};       // interior cells per direction
  std::array<int, 3> padded{1, 1, 1};  // with ghosts
  std::array<std::ptrdiff_t, 3> stride{1, 0, 0};
  std::array<double, 3> lower{0, 0, 0}, dx{1, 1, 1};  // of the whole mesh
  std::array<int, 3> first{0, 0, 0};                  // global index of this block's cell 0
  std::array<int, 3> mesh{1, 1, 1};                   // interior cells of the whole mesh per direction
  std::size_t total = 1;                              // padded cell count

  Grid() = default;
  // The whole mesh of `cells` between lo and hi.
  Grid(const std::array<int, 3>& cells, const std::array<double, 3>& lo, const std::array<double, 3>& hi)
      : Grid(cells, lo, hi, {0, 0, 0}, cells) {}
  // The block of `count` cells from global cell `from` of that mesh.
  Grid(const std::array<int, 3>& cells, const std::array<double, 3>& lo, const std::array<double, 3>& hi,
       const std::array<int, 3>& from, const std::array<int, 3>& count) {
    for (int d = 0; d < 3; ++d) {
      n[d] = d < DIM ? count[d] : 1;
      first[d] = d < DIM ? from[d] : 0;
      mesh[d] = d < DIM ? cells[d] : 1;
      padded[d] = d < DIM ? n[d] + 2 * NG : 1;
      lower[d] = lo[d];
      dx[d] = d < DIM ? (hi[d] - lo[d]) / cells[d] : 1.0;
    }
    stride = {1, padded[0], static_cast<std::ptrdiff_t>(padded[0]) * padded[1]};
    total = static_cast<std::size_t>(padded[0]) * padded[1] * padded[2];
  }

  static constexpr int offset(int d) { return d < DIM ? NG : 0; }
  // Linear index of interior-numbered cell (i,j,k); ghosts have negative or >= n indices.
  std::size_t index(int i, int j = 0, int k = 0) const {
    return static_cast<std::size_t>((i + offset(0)) + stride[1] * (j + offset(1)) + stride[2] * (k + offset(2)));
  }
  std::size_t interior_count() const { return static_cast<std::size_t>(n[0]) * n[1] * n[2]; }
  // Centre of block cell i along d (global index first + i).
  double center(int d, int i) const { return lower[d] + ((first[d] + i) + 0.5) * dx[d]; }
  // Whether this grid is the whole mesh (not one block of it).
  bool whole() const { return first == std::array<int, 3>{0, 0, 0} && n == mesh; }
  // Global index of padded index p's cell along each direction (ghost layers outside [0, mesh) included).
  std::array<int, 3> global_ijk(std::size_t p) const {
    const auto q0 = static_cast<std::size_t>(padded[0]), q1 = static_cast<std::size_t>(padded[1]);
    return {static_cast<int>(p % q0) - offset(0) + first[0], static_cast<int>((p / q0) % q1) - offset(1) + first[1],
            static_cast<int>(p / (q0 * q1)) - offset(2) + first[2]};
  }
  // Whether padded cell p is this block's in the whole mesh's count: an interior cell, or a ghost cell outside the
  // mesh on the side where the block meets the mesh's edge (a whole mesh: every padded cell).
  bool owns(std::size_t p) const {
    const std::array<int, 3> g = global_ijk(p);
    for (int d = 0; d < DIM; ++d) {
      const bool low = g[d] < first[d], high = g[d] >= first[d] + n[d];
      if ((low && first[d] != 0) || (high && first[d] + n[d] != mesh[d])) return false;
    }
    return true;
  }
  // Whether padded cell p is one of the block's own interior cells (no ghost layer).
  bool interior(std::size_t p) const {
    const std::array<int, 3> g = global_ijk(p);
    for (int d = 0; d < DIM; ++d)
      if (g[d] < first[d] || g[d] >= first[d] + n[d]) return false;
    return true;
  }
  // Whether padded cell p is a cell of the whole mesh: the block's own, or another block's in its ghost layers (not
  // a ghost layer of the mesh's edge).
  bool in_mesh(std::size_t p) const {
    const std::array<int, 3> g = global_ijk(p);
    for (int d = 0; d < DIM; ++d)
      if (g[d] < 0 || g[d] >= mesh[d]) return false;
    return true;
  }
  double cell_volume() const {
    double v = 1;
    for (int d = 0; d < DIM; ++d) v *= dx[d];
    return v;
  }
};

// The block of `count` cells from global cell `from` of g's mesh (same origin and spacing, bit for bit).
template <int DIM>
Grid<DIM> sub_grid(const Grid<DIM>& g, const std::array<int, 3>& from, const std::array<int, 3>& count) {
  Grid<DIM> b = g;
  for (int d = 0; d < 3; ++d) {
    b.n[d] = d < DIM ? count[d] : 1;
    b.first[d] = d < DIM ? from[d] : 0;
    b.padded[d] = d < DIM ? b.n[d] + 2 * Grid<DIM>::NG : 1;
  }
  b.stride = {1, b.padded[0], static_cast<std::ptrdiff_t>(b.padded[0]) * b.padded[1]};
  b.total = static_cast<std::size_t>(b.padded[0]) * b.padded[1] * b.padded[2];
  return b;
}

}  // namespace cosim::fluid
