// The elements of a solid mesh split into parts, one per rank, with METIS (Debian's libmetis-dev): a partition of
// the dual graph, elements joined where they share a face (2D: an edge), with the least cut for parts of equal size.
// METIS rather than Scotch: its mesh interface (METIS_PartMeshDual) takes the element connectivity as the mesh holds
// it, it is deterministic for a given input (the same parts on every rank that computes them), and Debian ships it.
// Arithmetic only, no MPI: every rank computes the same partition of the mesh it read.
#pragma once

#include <vector>

#include "solid_solver/mesh/mesh.h"

namespace cosim::solid {

struct MeshPartition {
  int parts = 1;
  std::vector<int> element_part;  // the part of each element
  // The part that owns each node (the lowest part among its elements): it sums the node's forces and masses.
  std::vector<int> node_owner;
  // Per part, the nodes it shares with other parts (ascending): their forces and masses are summed across parts.
  std::vector<std::vector<int>> shared_nodes;
  long cut_faces = 0;  // element faces between two parts
  std::vector<int> elements_per_part() const;
};

// `parts` parts of the mesh's elements (1: all in part 0). Throws std::invalid_argument when parts < 1 or the mesh
// has fewer elements than parts, std::runtime_error naming METIS's status when it fails.
MeshPartition partition_elements(const Mesh& m, int parts);

}  // namespace cosim::solid
