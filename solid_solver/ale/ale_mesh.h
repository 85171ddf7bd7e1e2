// Arbitrary Lagrangian-Eulerian (ALE) gas blocks of the solid solver: after a Lagrangian step the nodes that
// touch only relaxed blocks are moved to a better mesh (rezone.h) and the element and nodal state is carried
// over to it by fluxes through the swept faces (remap.h): Lagrange + rezone + remap (Hirt, Amsden and Cook,
// J. Comput. Phys. 14 (1974) 227; Benson, Comput. Methods Appl. Mech. Eng. 99 (1992) 235). This is what a
// conforming run needs around a deforming structure in a blast: the gas keeps a sound mesh, the structure stays
// Lagrangian, and the nodes they share move with the structure.
//
// AleMesh holds what is built once from the mesh: which nodes are relaxed, which of them lie on the exterior
// (held at their initial positions: an Eulerian boundary), the node neighbours of the mesh Laplacian, and the
// faces through which relaxed elements exchange (with each other, or with the outside).
#pragma once

#include <array>
#include <vector>

#include "solid_solver/mesh/mesh.h"

namespace cosim::solid {

struct AleFace {
  int a, local;  // element a and its local face (outward node order from a)
  int b;         // the element across the face, -1 for the exterior
};

struct AleMesh {
  std::vector<char> relaxed_element;              // element in a relaxed block
  std::vector<char> relaxed_node;                 // every element around the node is relaxed
  std::vector<char> exterior_node;                // a relaxed node on the mesh's exterior: held at its initial position
  std::vector<int> neighbour_offset, neighbours;  // CSR: nodes joined to each node by an element edge
  std::vector<AleFace> faces;                     // each interior face of two relaxed elements once, and the
                                                  // exterior faces of relaxed elements
};

// `relaxed_block[b]` marks the relaxed blocks.
AleMesh make_ale_mesh(const Mesh& m, const std::vector<char>& relaxed_block);

}  // namespace cosim::solid
