// Unstructured Lagrangian mesh: 4-node quadrilaterals (2D, plane strain) or 8-node hexahedra (3D), VTK node
// order, elements sorted by block so that each block is one contiguous element range.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace cosim::solid {

struct BoundaryFace {
  std::array<int, 4> nodes;  // 2 (2D segment) or 4 (3D quad) node ids, ordered so the normal points outward
  int element;               // owning element
};

struct Mesh {
  int dim = 3;
  int npe = 8;  // nodes per element: 4 (quad) or 8 (hex)
  int num_nodes = 0, num_elements = 0;
  std::vector<double> x0;          // initial coordinates, dim per node, interleaved [m]
  std::vector<int> conn;           // npe node ids per element (VTK order)
  std::vector<int> element_block;  // block index of each element
  std::vector<std::string> block_names;
  std::vector<std::array<int, 2>> block_range;  // [begin, end) element range of each block
  std::map<std::string, std::vector<int>> node_sets;
  std::map<std::string, std::vector<BoundaryFace>> face_sets;
  // Node -> corner (element*npe + local) lists (CSR), for the race-free gather of nodal forces.
  std::vector<int> node_corner_offset, node_corners;

  int face_nodes() const { return dim == 2 ? 2 : 4; }
};

// Structured box of nx x ny (x nz) cells on [lower, upper]; node and face sets x_lower, x_upper, y_lower, ...
// Every element gets block 0; use assign_blocks() afterwards.
Mesh make_box_mesh(int dim, const std::array<int, 3>& cells, const std::array<double, 3>& lower,
                   const std::array<double, 3>& upper);

// Reorders elements so that blocks are contiguous (stable), sets block_range, rebuilds face sets' element ids
// and the node-to-corner lists.
void finalize_mesh(Mesh& m);

// Element centroid (average of its nodes) from coordinates x (dim per node).
std::array<double, 3> element_centroid(const Mesh& m, const std::vector<double>& x, int e);

}  // namespace cosim::solid
