// Rezone of the relaxed (ALE) nodes: their displacement from the initial mesh is made harmonic (mesh-graph
// Laplacian, Jacobi sweeps warm-started from the last rezone), with the displacement of the Lagrangian nodes
// (the structure and the nodes it shares with the gas) and zero displacement on the exterior as boundary
// values. Far from the structure the gas mesh therefore stays the initial one (Eulerian), and the structure's
// motion is spread smoothly over the gas around it instead of crushing the first layer of elements.
#pragma once

#include <vector>

#include "solid_solver/ale/ale_mesh.h"

namespace cosim::solid {

// x: node positions after the Lagrangian step; on return the relaxed nodes hold their new positions.
// displacement: the relaxed nodes' displacement from x0 of the last rezone (warm start; dim per node).
void rezone(const Mesh& m, const AleMesh& a, int sweeps, std::vector<double>& displacement, std::vector<double>& x);

}  // namespace cosim::solid
