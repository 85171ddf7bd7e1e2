// Snapshot fields and summary of a fluid run.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>

#include "common/io/snapshot_writer.h"
#include "fluid_solver/core/simulation.h"

namespace cosim::fluid {

// The fields of a snapshot, computed from the simulation's state: per phase <phase>_alpha (two phases only),
// _density, _velocity, _pressure, _temperature (and _granular_temperature); for two phases the mixture's;
// embedded_category where bodies are embedded. `views` point into this object.
struct SnapshotFields {
  explicit SnapshotFields(const FluidSimulation& sim);
  SnapshotFields(const SnapshotFields&) = delete;
  SnapshotFields& operator=(const SnapshotFields&) = delete;
  std::size_t values_per_cell() const;  // doubles per cell in one snapshot

  std::vector<PhaseFields> ph;
  std::vector<double> mrho, mvel, mp, kind;
  std::vector<io::FieldView> views;
};

// What SnapshotFields(sim).values_per_cell() gives, from the scene alone (cosim check's snapshot size); the
// embedded categories are written where the scene has bodies or the run is coupled (from the first cycle on).
std::size_t snapshot_values_per_cell(const FluidScene& scene);

// Writes per phase: <phase>_alpha (two phases only), _density, _velocity, _pressure, _temperature;
// for two phases also mixture_density, mixture_velocity (mass-averaged), mixture_pressure (sum alpha p).
// The interface segments (CSV) go next to the snapshot: `segments`, or sim.interface_segments_csv().
// The snapshot's grid: the whole mesh (its origin and spacing), whatever block writes into it.
io::UniformGrid snapshot_grid(const FluidScene& scene);
void write_snapshot(io::SnapshotSeries& series, const FluidSimulation& sim);
void write_snapshot(io::SnapshotSeries& series, const FluidSimulation& sim, const std::string& segments);

nlohmann::json totals_json(const FluidScene& scene, const std::vector<PhaseTotals>& totals);

}  // namespace cosim::fluid
