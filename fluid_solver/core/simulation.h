// Type-erased handle on a fluid solver instance. The dimension, phase count and flux are
// compile-time parameters of the kernels; this interface is the one runtime seam, crossed once
// per time step, never per cell.
#pragma once

#include "common/app/run_driver.h"

#include <array>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/checkpoint/part_file.h"
#include "fluid_solver/core/block_links.h"
#include "fluid_solver/core/embedded_state.h"
#include "fluid_solver/core/pass_profile.h"
#include "fluid_solver/core/scene.h"

namespace cosim::fluid {

// Thrown when a state cannot be kept admissible (negative density, p + pinf <= 0, alpha outside (0,1)).
class StateError : public app::NumericalError {
 public:
  using app::NumericalError::NumericalError;
};

// Interior cell-centred fields of one phase, i fastest. velocity holds 3 components per cell.
struct PhaseFields {
  std::vector<double> alpha, rho, velocity, p, T;
  std::vector<double> theta;  // granular temperature [m^2/s^2] of a dispersed phase (docs/methods.md §2.9), else empty
};

// Primitive state of one phase in one cell (for coupling samples).
struct CellSample {
  double alpha = 1, rho = 0, p = 0, c = 0;  // [-], [kg/m^3], [Pa], [m/s]
  std::array<double, 3> velocity{0, 0, 0};  // [m/s]
  double granular = 0;                      // a dispersed phase's granular energy per unit mass [J/kg]
};

struct PhaseTotals {
  double mass = 0;
  std::array<double, 3> momentum{0, 0, 0};
  double energy = 0;
};

// Where the flow cells' mass of one phase went at an embedded boundary since the start (> 0: into the flow cells):
// through the wall faces (the ghost-cell wall's face fluxes, integrated with the Runge-Kutta weights: the mass a
// moving wall pushes through the fixed grid faces) and with the cells the body uncovered (+) or covered (-) when its
// geometry changed. totals() at the end - at the start = boundary_inflow + walls + cells, to round-off.
struct EmbeddedMassAccount {
  double walls = 0, cells = 0;
};

class FluidSimulation {
 public:
  virtual ~FluidSimulation() = default;
  virtual const FluidScene& scene() const = 0;
  virtual double time() const = 0;
  virtual long steps() const = 0;
  // Largest stable time step for the current state (CFL from the scene).
  virtual double stable_dt() = 0;
  // One full time step of size dt (all Runge-Kutta stages, relaxation and exchange sources).
  virtual void advance(double dt) = 0;
  virtual PhaseFields phase_fields(int phase) const = 0;
  // Mass, momentum and energy of each phase over the flow cells (fluid and fluid-cut).
  virtual std::vector<PhaseTotals> totals() const = 0;
  // What entered the flow cells through the domain boundary since the start (< 0: left), per phase: the
  // conservative part of the boundary faces' fluxes, integrated with the Runge-Kutta weights. With it
  // totals() at the end minus at the start minus this is what the scheme itself created (round-off without
  // bodies; with bodies also what crossed their walls).
  virtual std::vector<PhaseTotals> boundary_inflow() const = 0;
  // Per phase, the mass the embedded boundary moved into the flow cells since the start (EmbeddedMassAccount).
  virtual std::vector<EmbeddedMassAccount> embedded_mass_account() const = 0;
  // Per phase, what the embedded walls' face fluxes put into the flow cells since the start (mass, momentum,
  // energy; with embedded.conservative no mass: the wall's force and its work). Empty: not recorded.
  virtual std::vector<PhaseTotals> embedded_wall_exchange() const { return {}; }
  // States of the given padded cells, phase-major per cell: out[n * phases + k] (phases = scene().num_phases()).
  virtual void cell_states(const std::size_t* cells, std::size_t count, CellSample* out) const = 0;
  // Checkpoints: the whole evolving state (conserved variables of every cell as stored, time, steps, boundary
  // inflow), so that a restored solver continues bit for bit. restore_state throws std::runtime_error naming the
  // file and the entry when the part does not fit this scene (another mesh or phase set).
  virtual void save_state(checkpoint::PartWriter& w) const = 0;
  virtual void restore_state(const checkpoint::PartReader& r) = 0;
  // The conserved variables of the interior cells, variable-major, i fastest (what a checkpoint holds of the state;
  // the ghost layers are derived), and their restoration; conserved_cells().size() = variables x interior cells.
  virtual std::vector<double> conserved_cells() const = 0;
  virtual void set_conserved_cells(const std::vector<double>& values) = 0;
  virtual int conserved_vars() const = 0;
  // The scene's embedded bodies move with the steps: their vertices (x, y, z each) belong to the state (empty
  // without them); set_body_state places them and cuts them anew (on a split mesh every block together).
  virtual std::vector<double> body_state() const { return {}; }
  // On a split mesh, after every block has its links (set_block_links) and the blocks agreed that they are set up:
  // what needs the other blocks to begin (the embedded bodies' geometry and its far cells). Every block together.
  virtual void start_on_blocks() {}
  virtual void set_body_state(const std::vector<double>& /*vertices*/) {}
  // A conservative boundary's wall pressures per surface face (2 slots; NaN: none), sampled before a step's
  // redistribution, which a checkpoint's cells no longer show: they belong to the state too (empty: none). Alike on
  // every block of a split mesh. set_embedded_wall_pressure: before set_body_state, whose geometry takes them.
  virtual std::vector<double> embedded_wall_pressure() const { return {}; }
  virtual void set_embedded_wall_pressure(const std::vector<double>& /*slots*/) {}
  // The accounts that run with the state (a checkpoint's besides the cells): the boundary inflow's raw sums
  // (per phase mass, momentum[dim], energy) then the embedded mass through walls and by cells, per phase; with the
  // time and step count.
  virtual std::vector<double> account_values() const = 0;
  virtual void restore_progress(double time, long steps, const std::vector<double>& accounts) = 0;
  // On a block of a split mesh (scene().block): the links to the other blocks, which the solver keeps (not owned).
  virtual void set_block_links(BlockLinks* links) = 0;
  virtual std::size_t interior_cells() const = 0;
  virtual std::size_t state_bytes() const = 0;  // memory of all per-cell arrays
  // Bytes a time step reads and writes per cell in its passes over the grid (the benchmark's roofline; solver.h).
  virtual double traffic_bytes_per_cell_update() const = 0;
  // Per-pass clocks (pass_profile.h): switching them on or off zeroes them; pass_times() sums the threads.
  virtual void set_pass_profiling(bool on) = 0;
  virtual PassTimes pass_times() const = 0;
  // Embedded boundary of this cycle (categories, ghost records, wall faces); an inactive state
  // switches it off. `second_order` selects the face-state modification of paper steps 5-6.
  virtual void set_embedded(EmbeddedState state, bool second_order) = 0;
  // The wall velocities and pressures of the embedded state set last, in place (set_wall_values: one value per
  // EmbeddedState::wall_sources entry): the geometry, its volumes and the cells stay (a coupled cycle's interface
  // states, after the geometry of its faces).
  virtual void set_embedded_walls(const std::vector<WallValue>& values) = 0;
  // The state holds the cells as `elapsed` after the embedded geometry just set (a restored coupled cycle: its state
  // is after the step on that geometry); embedded.conservative reads its contents over the volumes of that time.
  virtual void set_embedded_elapsed(double elapsed) = 0;
  virtual const EmbeddedState& embedded() const = 0;
  // CellKind of every interior cell (i fastest) as numbers, for output.
  virtual std::vector<double> embedded_categories() const = 0;
  // Interface segments of this cycle (paper section 6), for output: one line per piece of the body
  // surface clipped to a cell, "i,j,k,cx,cy,cz,nx,ny,nz,area,vx,vy,vz" (CSV, SI). Empty without bodies.
  virtual std::string interface_segments_csv() const { return {}; }
};

std::unique_ptr<FluidSimulation> make_simulation(const FluidScene& scene);

// Advance with CFL-limited steps until t_target is reached exactly (or max_steps).
// Returns the number of steps taken.
long advance_to(FluidSimulation& sim, double t_target);

}  // namespace cosim::fluid
