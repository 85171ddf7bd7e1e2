// The Cartesian decomposition of a fluid mesh over ranks: how many blocks along each axis (the layout) and which
// cells each rank owns, in global cell indices. Pure arithmetic, no MPI: every rank computes the same answer, and
// the block coordinates of a cell come from the global mesh (a spacing recomputed per block would drift by an ulp).
//   const Layout l = choose_layout(4, 2, {1000, 1000, 1}, 3);   // {2, 2, 1}
//   const Block b = block_of(l, rank, {1000, 1000, 1});          // cells [lower, upper) per axis
#pragma once

#include <array>
#include <optional>
#include <string>

namespace cosim::parallel {

using Index3 = std::array<int, 3>;

struct Layout {
  Index3 blocks{1, 1, 1};  // blocks along x, y, z; their product is the number of ranks
  int ranks() const { return blocks[0] * blocks[1] * blocks[2]; }
};

struct Block {
  int rank = 0;
  Index3 coords{0, 0, 0};  // the block's position in the layout; rank = (coords[0] * by + coords[1]) * bz + coords[2]
  Index3 lower{0, 0, 0};   // its first cell along each axis (global index)
  Index3 upper{1, 1, 1};   // one past its last cell
  long cells() const { return long(upper[0] - lower[0]) * (upper[1] - lower[1]) * (upper[2] - lower[2]); }
};

// The layout of `ranks` blocks over a mesh of `cells` (1 along the axes beyond `dim`) with the least cut area (the
// halo the ranks exchange); ties go to the layout with the fewest blocks along x, then y: blocks keep whole rows of
// cells (x is the fastest index), so the ghost layers they exchange are contiguous and the inner loops long (3D
// 128^3 on 2 ranks: split along x, the exchange took 11% of the step; along z, see docs/parallel.md). Every block
// gets at least `min_cells` cells along a split axis (the stencil's reach: a halo comes from direct neighbours
// only). Throws std::invalid_argument saying why when no layout fits.
Layout choose_layout(int ranks, int dim, const Index3& cells, int min_cells);

// Checks a layout given by the scene (fluid.parallel.ranks): its product is `ranks`, it splits no axis beyond
// `dim`, and its blocks hold at least `min_cells` cells along each split axis. The reason, or nothing.
std::optional<std::string> layout_problem(const Layout& layout, int ranks, int dim, const Index3& cells, int min_cells);

// The cells [first, last) of part `part` of `n` cells in `parts` parts: the first n % parts parts one cell more.
std::array<int, 2> split(int n, int parts, int part);

// Rank `rank`'s block (row-major rank order, z fastest, as MPI_Cart_create with reorder off).
Block block_of(const Layout& layout, int rank, const Index3& cells);

// The rank owning global cell `cell`.
int owner_of(const Layout& layout, const Index3& cell, const Index3& cells);

}  // namespace cosim::parallel
