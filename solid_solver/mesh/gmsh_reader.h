// Gmsh mesh files, format 4.1 ASCII (https://gmsh.info/doc/texinfo/gmsh.html, "MSH file format").
// Physical groups of the mesh dimension (surfaces in 2D, volumes in 3D) name the element blocks; physical
// groups one dimension lower (curves in 2D, surfaces in 3D) name the boundary sets (node and face sets).
// Elements: 4-node quadrangles (type 3) in 2D, 8-node hexahedra (type 5) in 3D, with 2-node lines (type 1)
// or quadrangles as boundary elements; points (type 15) are ignored. Gmsh's node order of both is the VTK
// order used by the solver. Every error names the file and line, and the element, node or group.
#pragma once

#include <stdexcept>
#include <string>

#include "solid_solver/mesh/mesh.h"

namespace cosim::solid {

class MeshError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Reads the file; block_names are the element groups (in order of their physical tags), element_block
// indexes them; the mesh is not finalized. Throws MeshError "file:line: ..." for unreadable files, other
// format versions, unsupported element types, elements without a group, boundary elements that are not
// element faces, and inverted or degenerate elements (corner Jacobians <= 0).
Mesh read_gmsh(const std::string& path);

// Checks every element's corner Jacobians (the signed volume spanned by the edges at each corner): all must be
// > tol * (longest edge)^dim. Returns -1 when fine, else the first bad element and sets `what`.
int find_bad_element(const Mesh& m, std::string& what);

}  // namespace cosim::solid
