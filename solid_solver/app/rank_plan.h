// What a solid run on N ranks will be, for `--check --ranks N` (cosim check --solid-ranks N): the METIS parts as
// the ranks will compute them, each rank's owned and halo elements and its ghost nodes, without MPI.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "solid_solver/core/scene.h"
#include "solid_solver/mesh/mesh.h"

namespace cosim::solid {

// One plan line ("ranks: 3 (METIS parts), elements per rank ..."), and into `facts` the ranks, the most and fewest
// owned elements, the most halo elements and ghost nodes. Throws std::invalid_argument with the reason when the
// scene cannot run on `ranks` ranks, as the run would refuse it (ALE blocks, fewer elements than ranks).
std::string solid_rank_plan(const SolidScene& scene, const Mesh& mesh, int ranks, double bytes_per_element,
                            nlohmann::json& facts);

}  // namespace cosim::solid
