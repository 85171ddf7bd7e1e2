// summary.json of a fluid run (standalone or coupled).
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "fluid_solver/core/simulation.h"

namespace cosim::fluid {

struct RunRecord {
  std::string status = "running", error;
  double wall = 0;
  nlohmann::json start_totals;
  nlohmann::json extra = nlohmann::json::object();  // more top-level entries (e.g. "coupling")
  // On a split mesh, the whole mesh's figures (every rank's sums); otherwise the simulation's own are taken.
  std::optional<std::vector<PhaseTotals>> end_totals, inflow;
  std::optional<std::vector<EmbeddedMassAccount>> embedded_mass;
  std::optional<std::vector<PhaseTotals>> embedded_wall;  // FluidSimulation::embedded_wall_exchange
  std::optional<double> embedded_cells;                   // ghost and solid-cut cells
  double cells = 0;                                       // interior cells of the whole mesh; 0: the simulation's
};

void write_summary(const std::filesystem::path& dir, const FluidSimulation& sim, const RunRecord& rec);

}  // namespace cosim::fluid
