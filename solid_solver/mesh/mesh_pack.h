// A Mesh as one compact binary buffer and back, so that one rank can read a mesh file and hand the result to the
// others (docs/parallel.md, "The solid on many ranks"): the counts, then every array's raw bytes (coordinates as
// the doubles they are, so the copy is bit for bit), the names and the node and face sets. Not a file format: the
// buffer is read by the same build that wrote it.
#pragma once

#include <string>

#include "solid_solver/mesh/mesh.h"

namespace cosim::solid {

std::string pack_mesh(const Mesh& m);

// Throws MeshError ("<what>: ...") when the buffer is not a whole packed mesh (truncated, another layout).
Mesh unpack_mesh(const std::string& buffer, const std::string& what);

}  // namespace cosim::solid
