// How far the embedded boundary's conservative treatment reaches from a cell, in cells along every axis
// (docs/methods.md §5.8): the content of a cell a body covers or uncovers goes to (or comes from) the flow cells
// of the (2 r + 1)^DIM box around it. A mesh split over ranks needs this many layers of a neighbour's cells to
// do the same at a block edge.
#pragma once

namespace cosim::fluid {

inline constexpr int kRedistributionReach = 1;

}  // namespace cosim::fluid
