// The solid's part of a checkpoint set (solid.h5): the solver's state (Simulation::save_state), the snapshot series
// and block history so far, and the coupled runner's own state: the coupler's last InterfaceStates (applied again
// after the restore, and held over the substeps of the next cycle) and the run's counters.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "common/coupling/types.h"
#include "common/io/snapshot_writer.h"
#include "solid_solver/core/simulation.h"
#include "solid_solver/io/block_history.h"

namespace cosim::solid {

inline constexpr const char* kSolidPart = "solid.h5";

struct SolidRunState {
  long cycle = 0;   // coupled cycle of the set
  double time = 0;  // [s]
  EnergyBudget start;
  coupling::InterfaceStates last;  // the coupler's states of the set's cycle (face data only)
  bool apply_velocity = false;     // the states' interface velocities are imposed (modes impedance, characteristic)
  nlohmann::json counters = nlohmann::json::object();
};

// Writes DIR/solid.h5 (published whole); returns its file name. Throws std::runtime_error naming the file.
std::string write_solid_part(const std::filesystem::path& dir, const Simulation& sim, const io::SnapshotSeries& series,
                             const BlockHistory& history, const SolidRunState& run);

// Restores the solver from SET/solid.h5 and continues `series` (null: a rank that writes no outputs); the part stays
// open for the block history's resume. Throws std::runtime_error naming the file and the entry.
SolidRunState read_solid_part(const checkpoint::PartReader& part, Simulation& sim, io::SnapshotSeries* series);

}  // namespace cosim::solid
