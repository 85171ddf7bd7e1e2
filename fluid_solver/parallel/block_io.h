// A fluid run's outputs and accounts over the blocks of a split mesh: the global totals, one snapshot series (every
// rank writes its block into each snapshot file, collectively through parallel HDF5, so every reader sees one grid
// whatever the rank count) and checkpoint parts that hold the global state, restorable on another rank count. With
// one block, these are the run's own values.
#pragma once

#include <filesystem>
#include <vector>

#include "common/io/snapshot_writer.h"
#include "common/parallel/mpi/cart_comm.h"
#include "fluid_solver/app/fluid_checkpoint.h"
#include "fluid_solver/core/simulation.h"

namespace cosim::fluid {

// Every rank calls these together (they reduce or gather).
std::vector<PhaseTotals> totals_over_blocks(const FluidSimulation& sim, const parallel::CartComm& comm);
std::vector<PhaseTotals> inflow_over_blocks(const FluidSimulation& sim, const parallel::CartComm& comm);
// Per phase, what the walls' faces put into the flow cells (FluidSimulation::embedded_wall_exchange), over blocks.
std::vector<PhaseTotals> wall_exchange_over_blocks(const FluidSimulation& sim, const parallel::CartComm& comm);

// The embedded bodies' mass accounts and ghost and solid-cut cells of the whole mesh (sums over the blocks).
std::vector<EmbeddedMassAccount> embedded_mass_over_blocks(const FluidSimulation& sim, const parallel::CartComm& comm);
double embedded_cells_over_blocks(const FluidSimulation& sim, const parallel::CartComm& comm);
// The interface segment CSVs of the blocks (their own cells' rows) as one rank's file: the rows by cell in the mesh's
// order (rows of one cell keep their order).
std::string merge_segment_rows(const std::vector<std::string>& parts);

// The snapshot of the whole mesh; every rank keeps its `series` (rank 0's publishes the files). `segments`: this
// block's rows of the interface segments (a coupled run's boundary); null: the simulation's.
void write_snapshot_over_blocks(io::SnapshotSeries& series, const FluidSimulation& sim, const parallel::CartComm& comm,
                                const std::string* segments = nullptr);

// DIR/fluid.h5 with the global state, written by every rank together (its block of the cells; its file name on
// every rank). The entries are those of one rank's part (FluidSimulation::save_state), so a set restarts on any rank
// count. A coupled run passes its boundary (alike on every rank).
std::string write_fluid_part_over_blocks(const std::filesystem::path& dir, const FluidSimulation& sim,
                                         const io::SnapshotSeries& series, const FluidRunState& run,
                                         const parallel::CartComm& comm,
                                         const coupled::CoupledBoundary* boundary = nullptr);
// Restores every rank's block from SET/fluid.h5 (verified by rank 0, each rank reading its block) and continues
// rank 0's series.
FluidRunState read_fluid_part_over_blocks(const std::filesystem::path& set, FluidSimulation& sim,
                                          io::SnapshotSeries& series, const parallel::CartComm& comm,
                                          coupled::CoupledBoundary* boundary = nullptr);

}  // namespace cosim::fluid
