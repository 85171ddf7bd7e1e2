// summary.json of a solid run (standalone or coupled).
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "solid_solver/core/simulation.h"

namespace cosim::solid {

struct RunRecord {
  std::string status = "running", error;
  double wall = 0;
  EnergyBudget start;
  std::optional<EnergyBudget> end;                  // totals over the ranks (else sim.energy())
  nlohmann::json extra = nlohmann::json::object();  // more top-level entries (e.g. "coupling")
};

void write_summary(const std::filesystem::path& dir, const Simulation& sim, const RunRecord& rec);

}  // namespace cosim::solid
