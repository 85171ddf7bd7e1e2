// What a run on N ranks will be, for `--check --ranks N` (cosim check --fluid-ranks N): the layout of the blocks,
// the cells of the largest block and its share of the state, computed as the ranks will compute them, without MPI.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "fluid_solver/core/scene.h"

namespace cosim::fluid {

// One plan line ("ranks: 4, layout 2 x 2, ..."), and into `facts` the layout, the largest block's cells and its
// state bytes. Throws std::invalid_argument (or config::ConfigError) with the reason when the scene cannot run on
// `ranks` ranks, as the run would refuse it.
std::string rank_plan(const FluidScene& scene, int ranks, double state_bytes, nlohmann::json& facts);

}  // namespace cosim::fluid
