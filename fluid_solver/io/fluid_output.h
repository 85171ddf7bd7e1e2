// Snapshot fields and summary of a fluid run.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>

#include "common/io/snapshot_writer.h"
#include "fluid_solver/core/simulation.h"

namespace cosim::fluid {

// Writes per phase: <phase>_alpha (two phases only), _density, _velocity, _pressure, _temperature;
// for two phases also mixture_density, mixture_velocity (mass-averaged), mixture_pressure (sum alpha p).
// The interface segments (CSV) go next to the snapshot: `segments`, or sim.interface_segments_csv().
void write_snapshot(io::SnapshotSeries& series, const FluidSimulation& sim);
void write_snapshot(io::SnapshotSeries& series, const FluidSimulation& sim, const std::string& segments);

nlohmann::json totals_json(const FluidScene& scene, const std::vector<PhaseTotals>& totals);

}  // namespace cosim::fluid
