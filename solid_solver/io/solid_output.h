// Snapshots (HDF5 + XDMF via common/io/snapshot_writer.h) and summary.json of a solid run.
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>

#include "common/io/snapshot_writer.h"
#include "solid_solver/core/simulation.h"

namespace cosim::solid {

// Deformed mesh; node field velocity; cell fields density, pressure, viscosity, energy (specific),
// sound_speed, stress (Cauchy, symmetric tensor), plastic_strain, von_mises, block.
void write_snapshot(io::SnapshotSeries& series, const Simulation& sim);

nlohmann::json energy_json(const EnergyBudget& e);

}  // namespace cosim::solid
