// Conservative first-order remap of the relaxed (ALE) elements from the Lagrangian mesh to the rezoned one
// (donor cell through swept faces; Benson 1992, section 4). For each face the volume it sweeps between the
// two meshes, dV (exact: the swept quadrilateral in 2D, the swept hexahedron between the bilinear faces in 3D,
// so that the swept volumes of an element add up to its volume change), carries the donor element's densities
// across it: mass, internal energy and, for the staggered nodal velocities, momentum with the element-mean
// velocity. Node masses and momenta change by a 1/npe share of their elements' changes, so the total momentum
// is conserved and a uniform flow stays uniform. The kinetic energy the velocity averaging removes is put back
// as internal energy of the node's elements (DeBar's fix, DeBar 1974, UCID-19683), so total energy is
// conserved too. Through exterior faces (the Eulerian boundary) the element's own state flows out or in.
#pragma once

#include <vector>

#include "solid_solver/ale/ale_mesh.h"
#include "solid_solver/core/state.h"

namespace cosim::solid {

struct RemapFlux {
  double mass = 0, energy = 0;     // into the mesh through its exterior [kg], [J] (internal + kinetic)
  double momentum[3] = {0, 0, 0};  // [kg m/s]
  double kinetic_to_internal = 0;  // DeBar's fix [J]
};

// x_old: the Lagrangian positions; st.x: the rezoned ones. Updates st.emass, st.ie, st.vol, st.mass, st.v.
RemapFlux remap(const Mesh& m, const AleMesh& a, const std::vector<double>& x_old, State& st);

// Volume of element e at coordinates x (dim per node): the one-point element's exact volume (area x 1 m in 2D).
double element_volume(const Mesh& m, const std::vector<double>& x, int e);

// Volume swept by a face (node ids in outward order of its element) moving from x_old to x_new: positive when
// it moves outward (the element gains volume).
double swept_volume(int dim, const std::array<int, 4>& f, const std::vector<double>& x_old,
                    const std::vector<double>& x_new);

}  // namespace cosim::solid
