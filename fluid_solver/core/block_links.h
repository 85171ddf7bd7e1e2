// How one block of a split mesh meets the other blocks: the seam between the decomposition-blind solver and the
// module that moves data between ranks (fluid_solver/parallel). Crossed once per direction and Runge-Kutta stage,
// never per cell. A solver on the whole mesh has none.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "fluid_solver/core/layout.h"

namespace cosim::fluid {

class BlockLinks {
 public:
  virtual ~BlockLinks() = default;
  // The ghost layers along axis d of every variable of W on the sides the block's neighbours fill
  // (MeshBlock::exchanged), over the ghost layers of the axes before d: their cells' current values.
  virtual void exchange_ghosts(FieldArray& W, int d) = 0;
  // The largest of every block's `local` (the global wave rate that sets the step).
  virtual double max_over_blocks(double local) = 0;

  // Embedded bodies. Their records read cells beyond the ghost layers (fluid_solver/embedded/reach.h): those cells
  // (global indices; outside the mesh: the ghost layers of the block at that edge) come from their owners through
  // a sparse exchange, set up whenever the geometry changes. Channel 0: the primitives of every stage; channel 1:
  // the cell samples of the wall pressure. Every block calls plan_far together; it returns this block's padded
  // indices of the cells the others asked for, in the order their values go into exchange_far's `send`.
  virtual const std::vector<std::size_t>& plan_far(int channel, const std::vector<std::array<int, 3>>& cells) = 0;
  // plan_far's last answer for `channel`.
  virtual const std::vector<std::size_t>& far_send(int channel) const = 0;
  // `width` values per cell of plan_far's answer in `send`; `width` values per requested cell into `recv`.
  virtual void exchange_far(int channel, const double* send, double* recv, int width) = 0;
  // Whether `local` is true on any block (a failure agreed on before an exchange).
  virtual bool any(bool local) = 0;
  // Every block's `mine`, on every block, in rank order.
  virtual std::vector<std::string> texts_of_blocks(const std::string& mine) = 0;
};

}  // namespace cosim::fluid
