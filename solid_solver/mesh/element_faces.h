// Faces of the mesh elements: local face tables (outward node order), face geometry, the sorted list of all
// element faces (to match boundary elements of a mesh file and to find the exterior faces).
#pragma once

#include <array>
#include <cmath>
#include <vector>

#include "solid_solver/mesh/mesh.h"

namespace cosim::solid {

// Local faces with outward orientation: 2D quad edges (a, a+1) of a counter-clockwise quad; 3D VTK hex faces
// x-, x+, y-, y+, z-, z+ (counter-clockwise seen from outside).
inline constexpr int kQuadEdge[4][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
inline constexpr int kHexFace[6][4] = {{0, 4, 7, 3}, {1, 2, 6, 5}, {0, 1, 5, 4},
                                       {3, 7, 6, 2}, {0, 3, 2, 1}, {4, 5, 6, 7}};

inline int faces_per_element(int dim) { return dim == 2 ? 4 : 6; }

// Node ids of local face f of element e, outward order (2 or 4 entries; unused entries -1).
inline std::array<int, 4> element_face_nodes(const Mesh& m, int e, int f) {
  const int* c = &m.conn[static_cast<std::size_t>(e) * m.npe];
  if (m.dim == 2) return {c[kQuadEdge[f][0]], c[kQuadEdge[f][1]], -1, -1};
  return {c[kHexFace[f][0]], c[kHexFace[f][1]], c[kHexFace[f][2]], c[kHexFace[f][3]]};
}

// Area vector A n of a face (outward node order) from coordinates x (dim per node): 2D segment a-b
// (length x 1 m, n = (dy, -dx)/L), 3D bilinear quad (1/2 d13 x d24, exact for the projected area).
inline void face_area_vector(int dim, const double* x, const std::array<int, 4>& f, double an[3]) {
  if (dim == 2) {
    const double* a = x + 2 * static_cast<std::ptrdiff_t>(f[0]);
    const double* b = x + 2 * static_cast<std::ptrdiff_t>(f[1]);
    an[0] = b[1] - a[1];
    an[1] = -(b[0] - a[0]);
    an[2] = 0.0;
    return;
  }
  const double* p1 = x + 3 * static_cast<std::ptrdiff_t>(f[0]);
  const double* p2 = x + 3 * static_cast<std::ptrdiff_t>(f[1]);
  const double* p3 = x + 3 * static_cast<std::ptrdiff_t>(f[2]);
  const double* p4 = x + 3 * static_cast<std::ptrdiff_t>(f[3]);
  const double d1[3] = {p3[0] - p1[0], p3[1] - p1[1], p3[2] - p1[2]};
  const double d2[3] = {p4[0] - p2[0], p4[1] - p2[1], p4[2] - p2[2]};
  an[0] = 0.5 * (d1[1] * d2[2] - d1[2] * d2[1]);
  an[1] = 0.5 * (d1[2] * d2[0] - d1[0] * d2[2]);
  an[2] = 0.5 * (d1[0] * d2[1] - d1[1] * d2[0]);
}

struct FaceRef {
  std::array<int, 4> key;  // sorted node ids (2D: the last two are -1... sorted first) identifying the face
  int element, local;
};

// Sorted key of a face's nodes.
std::array<int, 4> face_key(int dim, const std::array<int, 4>& nodes);

// Every local face of every element, sorted by key (a face shared by two elements appears twice, adjacent).
std::vector<FaceRef> all_element_faces(const Mesh& m);

// Faces that belong to exactly one element, outward node order, sorted by (element, local face).
std::vector<BoundaryFace> exterior_faces(const Mesh& m);

// The axis (0, 1, 2) a planar face set is normal to, or -1 when the faces are not all in one plane
// x = const, y = const or z = const (relative tolerance tol on the normal directions).
int face_set_axis(const Mesh& m, const std::vector<double>& x, const std::vector<BoundaryFace>& faces,
                  double tol = 1e-9);

}  // namespace cosim::solid
