// The solid's exterior boundary (core/boundary_faces.h) as the protocol's interface faces
// (coupling::Faces, proto InterfaceFaces): geometry and states of every exterior face, with the face
// nodes renumbered compactly so that the fluid can rebuild a closed surface from them.
#pragma once

#include <vector>

#include "common/coupling/types.h"
#include "solid_solver/core/boundary_faces.h"
#include "solid_solver/core/state.h"

namespace cosim::solid {

struct InterfaceFaceMap {
  std::vector<int> vertex_node;            // mesh node of each interface vertex
  std::vector<std::uint32_t> face_vertex;  // nodes_per_face interface vertices per face
};

InterfaceFaceMap make_interface_face_map(const BoundaryFaces& bf);

// The faces at the current state (bf refreshed by Simulation::boundary_faces()).
coupling::Faces interface_faces(const BoundaryFaces& bf, const InterfaceFaceMap& map, const State& st);

}  // namespace cosim::solid
