// The standalone Lagrangian solid: mesh + state + one explicit leapfrog cycle.
// Cycle n -> n+1 (staggered: x, element state at t^n; v at t^{n-1/2}):
//   nodal_update(dt):   F = sum of corner forces + external loads; v^{n+1/2} = v^{n-1/2} + dt F / m;
//                       boundary conditions; x^{n+1} = x^n + dt v^{n+1/2}
//   element_update(dt): compatible energy, stress, EOS, viscosity, new corner forces, stable step
#pragma once

#include <Eigen/Dense>

#include <string>
#include <vector>

#include "common/checkpoint/part_file.h"
#include "solid_solver/ale/ale_mesh.h"
#include "solid_solver/ale/remap.h"
#include "solid_solver/core/boundary_faces.h"
#include "solid_solver/core/rank_links.h"
#include "solid_solver/core/rigid_body.h"
#include "solid_solver/core/scene.h"
#include "solid_solver/core/state.h"
#include "solid_solver/mesh/mesh.h"

namespace cosim::solid {

struct EnergyBudget {
  double internal = 0.0;       // [J]
  double kinetic = 0.0;        // [J], with v^{n-1/2}
  double boundary_work = 0.0;  // work done on the body by boundary forces since t = 0 [J]
  double ale_inflow = 0.0;     // energy that came in through the exterior of ALE blocks since t = 0 [J]
  double total() const { return internal + kinetic; }
  // What the energy must be from the start: start + boundary work + ALE inflow.
  double sources() const { return boundary_work + ale_inflow; }
};

class Simulation {
 public:
  explicit Simulation(const SolidScene& scene);
  // With a given mesh (tests: distorted meshes). Blocks are matched by index to scene.blocks; the box
  // regions of the scene are not applied.
  Simulation(const SolidScene& scene, Mesh mesh);

  // One full cycle with step dt; throws StateError on a numerical failure.
  void advance(double dt);
  // The two halves of a cycle (tests drive them separately).
  void nodal_update(double dt);
  void element_update(double dt);

  // Largest stable next step: cfl * element limit, at most dt_growth * last step (dt_initial first).
  double stable_dt() const;
  // The element that limits the step (the smallest size over sound speed and viscosity), its block, centroid
  // and state: what a step collapse is reported with.
  std::string limiting_step() const;
  double time() const { return t_; }
  long steps() const { return steps_; }
  const SolidScene& scene() const { return scene_; }
  const Mesh& mesh() const { return mesh_; }
  State& state() { return st_; }
  const State& state() const { return st_; }
  // With rank links: this rank's share (its nodes and elements; rank 0 also the rigid bodies and the energy
  // from before the links were set); the sum over the ranks is the total.
  EnergyBudget energy() const;
  // The run on several ranks (mesh/rank_part.h): from now on this rank updates its own nodes and the elements
  // around them, and reads the other ranks through `links` (kept, not owned). Throws std::invalid_argument for what
  // cannot run on several ranks (ALE blocks).
  void set_rank_links(RankLinks* links);
  const RankLinks* rank_links() const { return links_; }
  // With rank links (a collective call): rank 0's arrays get the state of every node and element from its owner,
  // and its energy sums the totals, so that rank 0 holds the whole state (snapshots, checkpoints, block history).
  // Without: nothing to do.
  void gather_state();
  // With rank links (a collective call): every rank's copy of the exterior faces' nodes (x, v) and of the elements
  // behind them (vol, p, q, c, s) from their owners, so that boundary_faces() and the interface loads computed from
  // it are on every rank what one rank computes (a coupled run: simulation_loads.cpp). Without: nothing to do.
  void share_boundary_state();
  // Exterior boundary faces for the coupling protocol, refreshed from the current state (t^n; velocities
  // v^{n-1/2}). The face list is built on the first call.
  const BoundaryFaces& boundary_faces();
  // Pressure per exterior face (boundary_faces() order) [Pa], applied from the next cycle on as the force
  // -p A n on the current face geometry, split equally between the face's nodes, in addition to the scene's
  // pressure boundaries; its work enters the boundary work. An empty vector removes it.
  void set_face_pressures(const std::vector<double>& p);
  // Interface normal velocity per exterior face (the coupler's u_I, paper eq. 22, applied with the pressure
  // as the interface condition of paper section 8, step 1) for the faces marked in `wetted`: at the start
  // of the next cycle each deformable node of wetted faces gets the velocity that meets v . n_f = u_f on
  // its wetted faces in the least-squares sense (area-weighted; only the directions the faces constrain
  // change: a flat face sets the normal component, a corner the whole vector). Rigid-block nodes and fixed
  // components are left alone. The kinetic-energy change is counted as boundary work. Used once.
  void set_face_normal_velocities(const std::vector<double>& u, const std::vector<char>& wetted);
  // The fluid's impedance Z per exterior face (coupling.mode robin, with set_face_pressures): the pressure on a
  // face becomes p + Z (v . n - v_sent), v_sent its normal velocity in the last boundary_faces(), with v the
  // new velocity of its nodes, solved implicitly in each step (docs/methods.md §4.4); faces with Z = 0 keep
  // the explicit pressure. Rigid blocks take it on their translation and rotation. An empty vector removes it.
  void set_face_impedances(const std::vector<double>& z);
  // Through the exterior of the ALE blocks since t = 0 (inflow positive) and the kinetic energy turned into heat.
  const RemapFlux& ale_flux() const { return ale_total_; }
  // Rigid blocks (blocks[].rigid), in block order.
  const std::vector<RigidBody>& rigid_bodies() const { return rigid_; }
  // Checkpoints (simulation_checkpoint.cpp): the evolving state, restored bit for bit; restore_state throws
  // std::runtime_error naming the file and the entry when the part does not fit this mesh.
  void save_state(checkpoint::PartWriter& w) const;
  void restore_state(const checkpoint::PartReader& r);
  // Bytes of state per element (nodal arrays apportioned), for the benchmark report.
  double bytes_per_element() const;

 private:
  void setup();
  void apply_boundary_conditions();
  void apply_pressure_loads();
  void ale_step();
  double absorbing_pressure(const BoundaryFace& f, const double* an) const;

  SolidScene scene_;
  Mesh mesh_;
  State st_;
  double t_ = 0.0, last_dt_ = 0.0, dt_elem_ = 0.0;
  long steps_ = 0;
  double ie_sum_ = 0.0, ke_ = 0.0, wb_ = 0.0;
  struct Load {
    const std::vector<BoundaryFace>* faces;
    double pressure, ramp;
    bool absorbing = false;  // NonReflecting: + rho c v.n of the face's element
  };
  std::vector<Load> loads_;
  std::unique_ptr<AleMesh> ale_;
  std::vector<double> ale_disp_, ale_x_lag_;
  RemapFlux ale_total_;  // accumulated over the run
  std::vector<RigidBody> rigid_;
  BoundaryFaces faces_;
  bool faces_built_ = false;
  void apply_interface_velocities();
  struct InterfaceNode {  // a node with an interface velocity for the next cycle
    int node;
    Eigen::Matrix3d N;     // sum over its wetted faces of A n n^T
    Eigen::Vector3d c;     // sum of A u_I n
    Eigen::Matrix3d pinv;  // pseudo-inverse of N over the constrained directions
  };
  std::vector<InterfaceNode> iface_;
  std::vector<double> face_p_;  // coupler pressures per exterior face [Pa] (empty: none)
  // Robin interface nodes: slot per node (-1: none), per slot K (3x3, row-major) and b (3) of impedance_update.
  std::vector<int> robin_slot_;
  std::vector<double> robin_K_, robin_b_;
  double rigid_ie_ = 0.0;  // internal energy of the rigid elements (constant) [J]
  std::vector<int> loaded_nodes_;
  RankLinks* links_ = nullptr;
  // share_boundary_state(): the exterior faces' nodes and elements (ascending), their owners, a packing buffer.
  std::vector<int> shared_nodes_, shared_node_owner_, shared_elements_, shared_element_owner_;
  std::vector<double> shared_buf_;
  std::vector<double> rigid_f_;  // per rigid node, its net force (rigid_node_forces)
  void advance_rigid_bodies(double dt, double t_half, double& ke, double& wb);
};

// Mesh for a scene: the box generator with blocks assigned by regions (later regions win; the rest belongs
// to the first block). Throws config::ConfigError-free std::runtime_error naming an empty block.
Mesh build_mesh(const SolidScene& scene);

}  // namespace cosim::solid
