// Exterior boundary of the solid for the coupling protocol: every element face that belongs to exactly one
// element (segments in 2D, bilinear quads in 3D), as a plain structure of arrays. Topology is found once
// (mesh/element_faces.h); geometry and states are refreshed from the current state on request.
#pragma once

#include <string>
#include <vector>

#include "solid_solver/core/state.h"
#include "solid_solver/mesh/mesh.h"

namespace cosim::solid {

struct BoundaryFaces {
  int dim = 3;
  int nodes_per_face = 4;  // 2 (2D) or 4 (3D)
  int count = 0;
  // Topology (fixed).
  std::vector<int> nodes;    // nodes_per_face per face, ordered so that the normal points out of the body
  std::vector<int> element;  // the adjacent element
  std::vector<int> block;    // its block
  std::vector<int> set;      // index into set_names of a boundary set containing the face, -1 if none
  std::vector<std::string> set_names;
  // Geometry and state at t^n (velocity: v^{n-1/2}, the last half-step velocity).
  std::vector<double> normal;         // unit outward normal, dim per face
  std::vector<double> area;           // [m^2]; 2D: length x 1 m
  std::vector<double> centre;         // mean of the face's nodes, dim per face [m]
  std::vector<double> velocity;       // mean of the face's node velocities, dim per face [m/s]
  std::vector<double> normal_stress;  // n . sigma . n of the adjacent element, sigma = s - (p + q) 1 [Pa]
                                      // (tension positive; 0 for rigid blocks)
  std::vector<double> impedance;      // rho c [Pa s/m], c the longitudinal speed sqrt((K + 4/3 G)/rho) with
                                      // strength, the bulk sound speed without; +inf for rigid blocks
};

// Topology of the exterior faces of m (and the sets of m.face_sets that contain them).
BoundaryFaces make_boundary_faces(const Mesh& m);

// Geometry and states from st; rigid[b] marks rigid blocks.
void update_boundary_faces(BoundaryFaces& bf, const State& st, const std::vector<char>& rigid);

}  // namespace cosim::solid
