// Every reach of the embedded boundary beyond a cell, in one place: how far (in cells, per direction) the records of
// a cell read other cells. A block of a split mesh builds its geometry over its cells plus margin_cells() of the
// mesh around them (clipped to the mesh), and every reach is checked against what the block has: beyond it is an
// error (ReachError), never a clamp.
//   - image points (image_points.h, thin_body.h): x_IP = x_G + (2 |phi_G| + pushes h) n, |phi_G| <= ghost_layers h
//     for a ghost (categorize.h), h the largest spacing; the (bi/tri)linear stencil adds one cell;
//   - the wall-velocity limiter (solver_embedded_faces.h): cells 1 to 4 from the wall along the grid line;
//   - the wall pressure samples (interface_samples.h): the face centre out by (1 + pushes + 1) h' with
//     h' = sum_d |n_d| dx_d <= sum_d dx_d, one stencil cell more;
//   - redistribution (embedded.conservative, docs/methods.md §5.8): the content of a cell a body covers or uncovers
//     goes to (or comes from) the flow cells of the (2 r + 1)^DIM box around it, r = kRedistributionReach; on one
//     rank only for now (fluid_layout refuses it on several: the boxes do not cross block borders yet).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace cosim::fluid::embedded {

inline constexpr int kWallLimiterReach = 4;     // cells 1..4 of a wall face (the flow cell and three beyond it)
inline constexpr int kRedistributionReach = 1;  // embedded.conservative: covered and uncovered cells
inline constexpr int kCategoryReach = 2;        // a ghost is a solid cell within this many cells of a flow cell
inline constexpr int kMaxImagePushes = 2;       // ImagePointOptions::max_pushes, SampleOptions::max_pushes

// A record that would read a cell this block does not have.
struct ReachError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Cells along direction d that an image-point stencil reaches from its ghost cell.
template <int DIM>
int image_point_reach(const std::array<double, 3>& dx, int d) {
  double hmax = 0;
  for (int e = 0; e < DIM; ++e) hmax = std::max(hmax, dx[static_cast<std::size_t>(e)]);
  const double distance = (2.0 * kCategoryReach + kMaxImagePushes) * hmax;
  return static_cast<int>(std::ceil(distance / dx[static_cast<std::size_t>(d)])) + 1;
}

// Cells along d that a wall pressure sample reaches from the surface point of a ghost's record (which lies within
// kCategoryReach h of the ghost cell).
template <int DIM>
int sample_reach(const std::array<double, 3>& dx, int d) {
  double hmax = 0, hsum = 0;
  for (int e = 0; e < DIM; ++e) {
    hmax = std::max(hmax, dx[static_cast<std::size_t>(e)]);
    hsum += dx[static_cast<std::size_t>(e)];
  }
  const double distance = kCategoryReach * hmax + (kMaxImagePushes + 2) * hsum;
  return static_cast<int>(std::ceil(distance / dx[static_cast<std::size_t>(d)])) + 1;
}

// The margin of mesh cells a block builds its geometry over beyond its ghost layers (ng), along d: the farthest
// reach of a record of its padded cells, and the cells the category test of the farthest of those looks at.
template <int DIM>
int margin_cells(const std::array<double, 3>& dx, int d, int ng) {
  const int reach =
      std::max({image_point_reach<DIM>(dx, d), sample_reach<DIM>(dx, d), kWallLimiterReach - 1, kRedistributionReach});
  return ng + reach + kCategoryReach;
}

}  // namespace cosim::fluid::embedded
