// The fluid side of one coupled cycle (paper section 8; docs/protocol.md): the solid's faces from the
// coupler become the embedded boundary of this cycle, the fluid is sampled next to each face, and the
// coupler's interface states set the wall velocity the ghost cells and the face states use.
// One runtime seam (the grid dimension); the work itself is compiled per dimension.
#pragma once

#include <memory>
#include <string>

#include "common/coupling/types.h"
#include "fluid_solver/core/block_links.h"
#include "fluid_solver/core/simulation.h"

namespace cosim::fluid::coupled {

class CoupledBoundary {
 public:
  virtual ~CoupledBoundary() = default;
  // Step 2: faces at t^{n+1} (placed back at t^n by `dt` times their velocity) -> clipping, signed
  // distance, categories, image points; returns the fluid samples per face and phase.
  // Throws std::invalid_argument for malformed faces and std::runtime_error for unusable geometry.
  virtual coupling::FluidSamples receive_faces(const coupling::Faces& faces, double dt) = 0;
  // Steps 3-6: interface normal velocity per face (eq. 22; the alpha-weighted mean over phases where
  // the fluid has two) -> the solver's embedded state for the coming step.
  virtual void apply_states(const coupling::InterfaceStates& states) = 0;
  virtual std::string segments_csv() const = 0;
  // Checkpoints: this cycle's faces, samples and states; restore() sets the same embedded boundary in the solver
  // again (the next cycle's time-step proposal is taken with it, before that cycle's states arrive).
  virtual void save(checkpoint::PartWriter& w) const = 0;
  virtual void restore(const checkpoint::PartReader& r) = 0;
  virtual double geometry_seconds() const = 0;  // total spent in the geometry [s]
  // On a block of a split mesh: the other blocks (every block then makes every call above together; the samples
  // returned are the whole interface's, each face sampled by the block holding its centre).
  virtual void set_block_links(BlockLinks* links) = 0;
  // The samples' normal velocity extrapolated to the wall like the pressure (coupling.mode robin, whose
  // solid weighs u_f - u_s by the fluid's impedance; interface_samples.h). Off: the sample point's value.
  void sample_wall_velocity(bool on) { wall_velocity_ = on; }

 protected:
  bool wall_velocity_ = false;
};

// For a 1D, 2D or 3D simulation.
std::unique_ptr<CoupledBoundary> make_coupled_boundary(FluidSimulation& sim);

// A coupled scene's structure must lie in the background (faces on its boundary are fine): throws
// std::invalid_argument naming the first vertex (or face centre) outside fluid.mesh. The runner checks the first
// faces it receives; the boundary itself accepts bodies partly outside (a piston entering the domain in tests).
void check_structure_inside_domain(const FluidScene& scene, const coupling::Faces& faces);

}  // namespace cosim::fluid::coupled
