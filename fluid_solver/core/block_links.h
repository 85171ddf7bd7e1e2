// How one block of a split mesh meets the other blocks: the seam between the decomposition-blind solver and the
// module that moves data between ranks (fluid_solver/parallel). Crossed once per direction and Runge-Kutta stage,
// never per cell. A solver on the whole mesh has none.
#pragma once

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
};

}  // namespace cosim::fluid
