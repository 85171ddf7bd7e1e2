// How a fluid scene's mesh is split over the ranks of a run: the layout of blocks (fluid.parallel.ranks, or the
// least cut area), what cannot run on more than one block yet, and each rank's MeshBlock with its links.
#pragma once

#include <memory>

#include "common/parallel/mpi/cart_comm.h"
#include "fluid_solver/core/block_links.h"
#include "fluid_solver/core/grid.h"
#include "fluid_solver/core/scene.h"

namespace cosim::fluid {

// Cells a block needs along a split axis: the ghost layers it hands its neighbours come from its own cells.
inline constexpr int kMinBlockCells = Grid<1>::NG;

// The layout for `ranks` ranks: the scene's fluid.parallel.ranks when given (checked), else the one with the least
// cut area. Throws config::ConfigError naming the scene's key (or std::invalid_argument) when none fits, and
// refuses what does not run on several blocks yet (embedded bodies, a coupled fluid).
parallel::Layout fluid_layout(const FluidScene& scene, int ranks);

// Per axis: the two end blocks are neighbours (a periodic axis split into several blocks).
std::array<bool, 3> periodic_axes(const FluidScene& scene);

// The scene's block on this rank (scene.block), from the communicator's block of the mesh.
void assign_block(FluidScene& scene, const parallel::CartComm& comm);

// The solver's links to the other blocks over the communicator (ghost exchanges of the primitives, the step).
class CartBlockLinks final : public BlockLinks {
 public:
  CartBlockLinks(parallel::CartComm& comm, const FluidScene& scene);
  void exchange_ghosts(FieldArray& W, int d) override;
  double max_over_blocks(double local) override { return comm_.max(local); }
  const std::vector<std::size_t>& plan_far(int channel, const std::vector<std::array<int, 3>>& cells) override;
  const std::vector<std::size_t>& far_send(int channel) const override {
    return far_send_[static_cast<std::size_t>(channel)];
  }
  void exchange_far(int channel, const double* send, double* recv, int width) override;
  bool any(bool local) override { return comm_.any(local); }
  std::vector<std::string> texts_of_blocks(const std::string& mine) override {
    return comm_.gather_text(mine, true, &texts_timing_);
  }
  // The time of texts_of_blocks so far (a coupled fluid's samples merged over the blocks).
  const parallel::TextTiming& texts_timing() const { return texts_timing_; }

 private:
  parallel::CartComm& comm_;
  parallel::PaddedBox box_;
  std::vector<double*> vars_;
  std::array<parallel::SparsePlan, 2> far_plans_;
  std::array<std::vector<std::size_t>, 2> far_send_;
  parallel::TextTiming texts_timing_;
};

}  // namespace cosim::fluid
