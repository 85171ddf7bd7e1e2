// Rigid blocks (blocks[].rigid): translation under a constant pressure accelerates at exactly F/m; a free
// spinning block keeps its shape and angular momentum; the skip path leaves the block's elements untouched.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>

#include "solid_test_util.h"

using namespace cosim::solid;

namespace {
double max_distance_change(const Simulation& sim) {
  const Mesh& m = sim.mesh();
  const int D = m.dim;
  double worst = 0.0;
  for (int a = 0; a < m.num_nodes; a += 3)
    for (int b = a + 1; b < m.num_nodes; b += 2) {
      double d0 = 0, d1 = 0;
      for (int d = 0; d < D; ++d) {
        const double e0 = m.x0[a * D + d] - m.x0[b * D + d];
        const double e1 = sim.state().x[a * D + d] - sim.state().x[b * D + d];
        d0 += e0 * e0;
        d1 += e1 * e1;
      }
      worst = std::max(worst, std::abs(std::sqrt(d1) - std::sqrt(d0)));
    }
  return worst;
}
}  // namespace

// 2D and 3D: p = 1e5 Pa on x_lower of a 2 x 1 (x 1) m block, rho = 100 kg/m^3 -> a = p A / m = 500 m/s^2.
TEST(SolidRigid, ConstantPressureAcceleratesAtFOverM) {
  for (int dim : {2, 3}) {
    const std::string cells = dim == 2 ? "[4, 2]" : "[4, 2, 2]", up = dim == 2 ? "[2, 1]" : "[2, 1, 1]";
    SolidScene s = parse_solid_scene(fmt::format(R"(
solid:
  mesh: {{cells: {}, upper: {}}}
  blocks:
    - {{name: piston, rigid: true, density: 100.0}}
  boundaries:
    - {{set: x_lower, type: pressure, value: 1.0e5}}
  time: {{end: 1.0}}
)",
                                                 cells, up));
    Simulation sim(s);
    ASSERT_EQ(sim.rigid_bodies().size(), 1u);
    const double m = 200.0, a = 1e5 / m, dt = 1e-4;
    EXPECT_NEAR(sim.rigid_bodies()[0].mass, m, 1e-10 * m);
    const double e0 = sim.energy().total();
    for (int i = 0; i < 100; ++i) sim.advance(dt);
    const auto& rb = sim.rigid_bodies()[0];
    // Leapfrog: V^{n+1/2} = V^{n-1/2} + dt F/m exactly, so V = a t after n steps.
    EXPECT_NEAR(rb.V[0], a * sim.time(), 1e-12 * a * sim.time()) << dim << "D";
    for (int d = 1; d < dim; ++d) EXPECT_EQ(rb.V[d], 0.0);
    for (int n = 0; n < sim.mesh().num_nodes; ++n)
      EXPECT_NEAR(sim.state().v[n * dim], a * sim.time(), 1e-10) << "node " << n;
    EXPECT_LT(max_distance_change(sim), 1e-13);
    // Skip path: no pressure, viscosity or corner forces in the rigid elements; energy balance exact.
    for (int z = 0; z < sim.mesh().num_elements; ++z) {
      EXPECT_EQ(sim.state().p[z], 0.0);
      EXPECT_EQ(sim.state().q[z], 0.0);
    }
    for (double f : sim.state().fc) EXPECT_EQ(f, 0.0);
    const auto e = sim.energy();
    EXPECT_NEAR(e.kinetic, 0.5 * m * rb.V[0] * rb.V[0], 1e-10 * e.kinetic);
    EXPECT_NEAR(e.total() - e0, e.boundary_work, 1e-10 * e.kinetic);
  }
}

// A free block spinning at 10 rad/s keeps its shape, its centre and its angular momentum (2D: I w exactly;
// 3D about a non-principal axis: L constant, kinetic energy 1/2 L . omega conserved).
TEST(SolidRigid, SpinningBlockKeepsShapeAndAngularMomentum) {
  for (int dim : {2, 3}) {
    const std::string cells = dim == 2 ? "[4, 2]" : "[4, 2, 3]", up = dim == 2 ? "[2, 1]" : "[2, 1, 1.5]";
    const std::string w = dim == 2 ? "10.0" : "[3.0, -4.0, 8.0]";
    SolidScene s = parse_solid_scene(fmt::format(R"(
solid:
  mesh: {{cells: {}, upper: {}}}
  blocks:
    - {{name: wheel, rigid: true, density: 7800.0, initial: {{angular_velocity: {}, velocity: {}}}}}
  time: {{end: 1.0}}
)",
                                                 cells, up, w, dim == 2 ? "[1.0, 0.0]" : "[1.0, 0.0, 0.0]"));
    Simulation sim(s);
    const RigidBody rb0 = sim.rigid_bodies()[0];
    const double ke0 = rigid_body_kinetic_energy(rb0, dim);
    if (dim == 2) { EXPECT_NEAR(rb0.L[2], rb0.I0[2][2] * 10.0, 1e-9 * std::abs(rb0.L[2])); }
    for (int i = 0; i < 2000; ++i) sim.advance(1e-3);  // 20 rad: about three turns
    const auto& rb = sim.rigid_bodies()[0];
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(rb.L[d], rb0.L[d], 1e-9 * std::abs(rb0.L[2])) << dim << "D";
    EXPECT_NEAR(rb.X[0], rb0.X[0] + 2.0, 1e-12);
    EXPECT_LT(max_distance_change(sim), 1e-12);
    EXPECT_NEAR(rigid_body_kinetic_energy(rb, dim), ke0, (dim == 2 ? 1e-12 : 1e-5) * ke0);
    // The nodes turned: the first node is not where pure translation would put it.
    double moved = 0.0;
    for (int d = 0; d < dim; ++d) moved += std::abs(sim.state().x[d] - sim.mesh().x0[d] - (d == 0 ? 2.0 : 0.0));
    EXPECT_GT(moved, 0.1);
    std::printf("[ measured ] %dD spin: shape change %.2e m, |dL| %.2e, kinetic energy drift %.2e\n", dim,
                max_distance_change(sim), std::abs(rb.L[2] - rb0.L[2]), rigid_body_kinetic_energy(rb, dim) / ke0 - 1.0);
  }
}

// Velocity boundaries on a rigid block's nodes fix that component of the whole body and its rotation.
TEST(SolidRigid, ConstrainedComponentsAndInputErrors) {
  SolidScene s = parse_solid_scene(R"(
solid:
  mesh: {cells: [4, 2], upper: [2, 1]}
  blocks:
    - {name: piston, rigid: true, density: 100.0}
  boundaries:
    - {set: y_lower, type: symmetry}
    - {set: x_lower, type: pressure, value: 1.0e5}
    - {set: y_upper, type: pressure, value: 3.0e5}
  time: {end: 1.0}
)");
  Simulation sim(s);
  for (int i = 0; i < 50; ++i) sim.advance(1e-4);
  const auto& rb = sim.rigid_bodies()[0];
  EXPECT_TRUE(rb.rotation_locked);
  EXPECT_EQ(rb.V[1], 0.0);
  EXPECT_NEAR(rb.V[0], 500.0 * sim.time(), 1e-9);
  EXPECT_LT(max_distance_change(sim), 1e-13);
  // The reaction of the symmetry plane does no work: the balance still closes.
  const auto e = sim.energy();
  EXPECT_NEAR(e.total(), e.boundary_work, 1e-10 * e.kinetic);
  // A rigid block with strength is rejected with the key named.
  try {
    parse_solid_scene(R"(
solid:
  mesh: {cells: [2, 2], upper: [1, 1]}
  blocks:
    - {name: p, rigid: true, density: 1.0, strength: {shear_modulus: 1.0}}
  time: {end: 1.0}
)");
    ADD_FAILURE() << "no error";
  } catch (const cosim::config::ConfigError& err) {
    EXPECT_NE(std::string(err.what()).find("strength"), std::string::npos) << err.what();
  }
}

// Torque: a pressure on the right half of the top face of a free 2 x 1 block turns it clockwise at
// dL/dt = T = -p (1 m) (0.5 m) about the centre of mass, while the centre accelerates at F/m.
TEST(SolidRigid, OffCentreLoadGivesTorque) {
  SolidScene s = parse_solid_scene(R"(
solid:
  mesh: {cells: [4, 2], upper: [2, 1]}
  blocks:
    - {name: block, rigid: true, density: 100.0}
  time: {end: 1.0}
)");
  Simulation sim(s);
  const BoundaryFaces& bf = sim.boundary_faces();
  std::vector<double> p(bf.count, 0.0);
  for (int i = 0; i < bf.count; ++i)
    if (bf.normal[2 * i + 1] > 0.5 && bf.centre[2 * i] > 1.0) p[i] = 1e3;
  sim.set_face_pressures(p);
  for (int i = 0; i < 100; ++i) sim.advance(1e-4);
  const auto& rb = sim.rigid_bodies()[0];
  const double t = sim.time(), m = 200.0;
  EXPECT_NEAR(rb.L[2], -1e3 * 0.5 * t, 1e-4 * 1e3 * 0.5 * t);  // the turn is tiny: T stays -p/2
  EXPECT_NEAR(rb.V[1], -1e3 / m * t, 1e-4 * 1e3 / m * t);
  EXPECT_LT(max_distance_change(sim), 1e-13);
}
