// Rigid blocks (blocks[].rigid: true): the nodes of a rigid block move as one rigid body under the net force
// and torque of the forces on them (corner forces of the neighbouring deformable elements, pressure loads,
// coupler tractions). Its own elements do no stress, EOS, viscosity or hourglass work: they are skipped.
// Leapfrog, staggered like the nodes (x at t^n; V, angular momentum L at t^{n-1/2}):
//   V^{n+1/2} = V^{n-1/2} + dt F^n / M,      L^{n+1/2} = L^{n-1/2} + dt T^n   (T about the centre of mass),
//   omega = I^{-1} L (I rotated with the body; 3D: I at the predicted mid-step orientation),
//   Q^{n+1} = exp(dt [omega]x) Q^n (Rodrigues),  X^{n+1} = X^n + dt V^{n+1/2},  x_i = X + Q r0_i.
// Node velocities are the chords (x_i^{n+1} - x_i^n)/dt, so the neighbouring elements see the exact motion,
// and the body keeps its shape to round-off. Prescribed velocity components on any of its nodes (fixed,
// symmetry, velocity boundaries) fix that translation component of the whole body and lock its rotation.
#pragma once

#include <array>
#include <vector>

#include "solid_solver/core/state.h"
#include "solid_solver/mesh/mesh.h"

namespace cosim::solid {

struct RigidBody {
  int block = -1;
  std::vector<int> nodes;  // every node of the block's elements
  std::vector<double> r0;  // body-frame node positions about the centre of mass (3 per node) [m]
  double mass = 0.0;       // sum of the lumped masses of its nodes [kg]
  double I0[3][3] = {};    // body-frame inertia tensor about the centre of mass [kg m^2]
  double Q[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};  // orientation (body -> world)
  double X[3] = {0, 0, 0};                             // centre of mass at t^n [m]
  double V[3] = {0, 0, 0};                             // velocity at t^{n-1/2} [m/s]
  double L[3] = {0, 0, 0};                         // angular momentum about the centre of mass at t^{n-1/2} [kg m^2/s]
  std::array<bool, 3> fixed{false, false, false};  // prescribed translation components
  double fixed_value[3] = {0, 0, 0};               // their values [m/s]
  double fixed_ramp = 0.0;                         // linear ramp time of the prescribed values [s]
  bool rotation_locked = false;
  // The fluid's Robin condition on the body (Simulation::set_face_impedances), sums over its nodes i with their
  // K_i, b_i and arms r_i: force b - K V and torque added_torque - C V - K_rot omega at the step's velocities,
  // taken implicitly (translation first, then rotation); zero when none. added_torque = sum r_i x b_i cancels
  // the impedance part of the explicit face loads, C = sum [r_i]x K_i, K_rot = sum [r_i]x K_i [r_i]x^T.
  double added_K[3][3] = {};     // [kg/s]
  double added_b[3] = {};        // [N]
  double added_torque[3] = {};   // [N m]
  double added_C[3][3] = {};     // [kg m/s]
  double added_Krot[3][3] = {};  // [kg m^2/s]
};

// Builds the body of block b from the current nodal positions, masses and velocities (its node velocities
// are replaced by the rigid-body field V + omega x r) and from the boundary-condition masks of its nodes.
// Throws std::runtime_error when the block shares a node with another rigid block (rigid_owner >= 0) or
// when its nodes carry conflicting prescribed velocities.
RigidBody make_rigid_body(const Mesh& m, int b, State& st, std::vector<int>& rigid_owner);

// One leapfrog step of the body (see the header comment). t_half = t^{n+1/2} for ramps. Adds the kinetic
// energy of its nodes at t^{n+1/2} to ke and the work of loads and constraint reactions to wb.
void advance_rigid_body(RigidBody& rb, const Mesh& m, State& st, double dt, double t_half, double& ke, double& wb);
// The same with the net force on each of its nodes given (3 per node, rb.nodes order; rigid_node_forces): a body
// whose nodes are owned by several ranks gets every node's force from its owner and sums them in that order.
void advance_rigid_body(RigidBody& rb, const Mesh& m, State& st, const double* node_force, double dt, double t_half,
                        double& ke, double& wb);
// The net force on each node of the body (3 per node, rb.nodes order): the corner forces of its elements in the
// node's corner order plus its external load. With owner (per mesh node), only the nodes owned by `rank`; the
// others get zero.
void rigid_node_forces(const RigidBody& rb, const Mesh& m, const State& st, const int* owner, int rank, double* f);

// Kinetic energy of the body: 1/2 M V^2 + 1/2 L . omega [J] (for tests).
double rigid_body_kinetic_energy(const RigidBody& rb, int dim);

}  // namespace cosim::solid
