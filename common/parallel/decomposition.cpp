#include "common/parallel/decomposition.h"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

namespace cosim::parallel {

namespace {
// The area of the faces between blocks (in cell faces): each of the blocks[d] - 1 cuts across axis d spans the
// mesh's other two extents.
double cut_area(const Index3& blocks, const Index3& cells) {
  double area = 0;
  for (int d = 0; d < 3; ++d) area += double(blocks[d] - 1) * double(cells[(d + 1) % 3]) * double(cells[(d + 2) % 3]);
  return area;
}

// The problem with blocks[d] blocks along axis d, or "".
std::string axis_problem(int d, int blocks, int dim, int cells, int min_cells) {
  static constexpr char kAxis[] = {'x', 'y', 'z'};
  if (blocks < 1) return fmt::format("{} blocks along {}: at least 1 expected", blocks, kAxis[d]);
  if (blocks > 1 && d >= dim) return fmt::format("{} blocks along {}, but the mesh is {}D", blocks, kAxis[d], dim);
  if (blocks > 1 && cells / blocks < std::max(min_cells, 1))
    return fmt::format("{} cells along {} cannot be split into {} blocks of at least {} cells (the stencil's reach)",
                       cells, kAxis[d], blocks, min_cells);
  return "";
}
}  // namespace

std::optional<std::string> layout_problem(const Layout& layout, int ranks, int dim, const Index3& cells,
                                          int min_cells) {
  for (int d = 0; d < 3; ++d)
    if (const std::string p = axis_problem(d, layout.blocks[d], dim, cells[d], min_cells); !p.empty()) return p;
  if (layout.ranks() != ranks)
    return fmt::format("{} x {} x {} blocks make {} ranks, but the run has {}", layout.blocks[0], layout.blocks[1],
                       layout.blocks[2], layout.ranks(), ranks);
  return std::nullopt;
}

Layout choose_layout(int ranks, int dim, const Index3& cells, int min_cells) {
  if (ranks < 1) throw std::invalid_argument(fmt::format("{} ranks: at least 1 expected", ranks));
  std::optional<Layout> best;
  double best_area = 0;
  // Every factorisation bx * by * bz = ranks (at most a few hundred even for 4096 ranks), in increasing bx, by:
  // the first of equal area found splits the slow axes most.
  for (int bx = 1; bx <= ranks; ++bx) {
    if (ranks % bx) continue;
    for (int by = 1; by <= ranks / bx; ++by) {
      if ((ranks / bx) % by) continue;
      const Layout l{{bx, by, ranks / bx / by}};
      if (layout_problem(l, ranks, dim, cells, min_cells)) continue;
      const double area = cut_area(l.blocks, cells);
      if (!best || area < best_area) best = l, best_area = area;
    }
  }
  if (!best)
    throw std::invalid_argument(fmt::format(
        "{} ranks cannot share a {}D mesh of {} x {} x {} cells in blocks of at least {} cells along each split axis "
        "(the stencil's reach): use fewer ranks or more cells",
        ranks, dim, cells[0], cells[1], cells[2], min_cells));
  return *best;
}

std::array<int, 2> split(int n, int parts, int part) {
  const int base = n / parts, extra = n % parts;
  const int first = part * base + std::min(part, extra);
  return {first, first + base + (part < extra ? 1 : 0)};
}

Block block_of(const Layout& layout, int rank, const Index3& cells) {
  if (rank < 0 || rank >= layout.ranks())
    throw std::invalid_argument(fmt::format("rank {} outside the layout of {} ranks", rank, layout.ranks()));
  Block b;
  b.rank = rank;
  const Index3& n = layout.blocks;
  b.coords = {rank / (n[1] * n[2]), (rank / n[2]) % n[1], rank % n[2]};
  for (int d = 0; d < 3; ++d) {
    const auto [first, last] = split(cells[d], n[d], b.coords[d]);
    b.lower[d] = first;
    b.upper[d] = last;
  }
  return b;
}

int owner_of(const Layout& layout, const Index3& cell, const Index3& cells) {
  Index3 c{};
  for (int d = 0; d < 3; ++d) {
    // The part holding index i: the larger parts come first (split), each base + 1 cells long.
    const int base = cells[d] / layout.blocks[d], extra = cells[d] % layout.blocks[d];
    const int in_large = extra * (base + 1);
    c[d] = cell[d] < in_large ? cell[d] / (base + 1) : extra + (cell[d] - in_large) / base;
  }
  return (c[0] * layout.blocks[1] + c[1]) * layout.blocks[2] + c[2];
}

}  // namespace cosim::parallel
