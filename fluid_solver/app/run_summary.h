// summary.json of a fluid run (standalone or coupled).
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "fluid_solver/core/simulation.h"

namespace cosim::fluid {

struct RunRecord {
  std::string status = "running", error;
  double wall = 0;
  nlohmann::json start_totals;
  nlohmann::json extra = nlohmann::json::object();  // more top-level entries (e.g. "coupling")
};

void write_summary(const std::filesystem::path& dir, const FluidSimulation& sim, const RunRecord& rec);

}  // namespace cosim::fluid
