// The fluid's part of a checkpoint set (fluid.h5): the solver's state (FluidSimulation::save_state), the snapshot
// series so far and the run's record, so that a restart continues the run and its outputs bit for bit.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "common/io/snapshot_writer.h"
#include "fluid_solver/core/simulation.h"
#include "fluid_solver/coupled/coupled_boundary.h"

namespace cosim::fluid {

inline constexpr const char* kFluidPart = "fluid.h5";

// What the runner keeps across a restart besides the solver and the series.
struct FluidRunState {
  long cycle = 0;   // coupled cycle (standalone: step) of the set
  double time = 0;  // [s]
  nlohmann::json start_totals;
  nlohmann::json counters = nlohmann::json::object();  // the runner's totals so far (solver seconds, ...)
};

// Writes DIR/fluid.h5 (published whole); returns its file name. Throws std::runtime_error naming the file.
// A coupled run passes its boundary (the embedded boundary of the set's cycle is restored with the solver).
std::string write_fluid_part(const std::filesystem::path& dir, const FluidSimulation& sim,
                             const io::SnapshotSeries& series, const FluidRunState& run,
                             const coupled::CoupledBoundary* boundary = nullptr);

// Restores the solver and continues `series` from SET/fluid.h5. Throws std::runtime_error naming the file and the
// entry when the part is missing or does not fit this scene.
FluidRunState read_fluid_part(const std::filesystem::path& set, FluidSimulation& sim, io::SnapshotSeries& series,
                              coupled::CoupledBoundary* boundary = nullptr);

}  // namespace cosim::fluid
