// Exterior boundary extraction for the coupling protocol: closed-surface identities (sum n A = 0) on
// distorted meshes, the area of a box, impedance of steel at rest, face states, and face pressures applied
// from outside (the coupler's entry point).
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "solid_test_util.h"

using namespace cosim::solid;

namespace {
SolidScene box_scene(const std::string& cells, const std::string& upper, const std::string& block) {
  return parse_solid_scene(fmt::format(R"(
solid:
  mesh: {{cells: {}, upper: {}}}
  blocks:
    - {}
  time: {{end: 1.0}}
)",
                                       cells, upper, block));
}
const char* kGas = "{name: gas, eos: {type: ideal_gas, gamma: 1.4}, density: 1.2, initial: {pressure: 1.0e5}}";
}  // namespace

TEST(SolidBoundaryFaces, ClosedSurfaceAndBoxArea) {
  for (int dim : {2, 3}) {
    SolidScene s = dim == 2 ? box_scene("[3, 2]", "[2, 1]", kGas) : box_scene("[3, 2, 2]", "[2, 1, 3]", kGas);
    // Every node (boundary ones too) moved by up to 10% of a cell: faces become non-planar in 3D.
    Mesh m = build_mesh(s);
    for (int n = 0; n < m.num_nodes; ++n)
      for (int d = 0; d < dim; ++d) m.x0[n * dim + d] += 0.1 * 0.33 * solid_test::hash_unit(n, d);
    Simulation distorted(s, m);
    const BoundaryFaces& bf = distorted.boundary_faces();
    EXPECT_EQ(bf.count, dim == 2 ? 10 : 32);
    double sum[3] = {0, 0, 0};
    for (int i = 0; i < bf.count; ++i)
      for (int d = 0; d < dim; ++d) sum[d] += bf.normal[i * dim + d] * bf.area[i];
    for (int d = 0; d < dim; ++d) EXPECT_NEAR(sum[d], 0.0, 1e-14) << dim << "D, component " << d;
    // Undistorted: the total area of the box, outward normals (n . (centre - box centre) > 0).
    Simulation box(s);
    const BoundaryFaces& b = box.boundary_faces();
    double area = 0;
    for (int i = 0; i < b.count; ++i) {
      area += b.area[i];
      const double mid[3] = {1.0, 0.5, 1.5};
      double dot = 0;
      for (int d = 0; d < dim; ++d) dot += b.normal[i * dim + d] * (b.centre[i * dim + d] - mid[d]);
      EXPECT_GT(dot, 0.0) << "face " << i;
      EXPECT_NEAR(b.normal_stress[i], -1e5, 1e-9);  // gas at rest: n.sigma.n = -p
      EXPECT_NEAR(b.impedance[i], 1.2 * std::sqrt(1.4e5 / 1.2), 1e-9);
      EXPECT_GE(b.set[i], 0);  // every face of the box lies in one of its side sets
    }
    EXPECT_NEAR(area, dim == 2 ? 6.0 : 22.0, 1e-12);  // 2D: perimeter x 1 m; 3D: 2 (2 + 6 + 3)
  }
}

// 4340 steel (rho0 = 7810, c0 = 4578, docs/methods.md §7.3) at rest: bulk impedance rho0 c0 = 3.575e7 Pa s/m; with
// G = 81.8 GPa the longitudinal speed c_p = sqrt(c0^2 + 4G/(3 rho0)) = 5909.6 m/s gives 4.6154e7.
TEST(SolidBoundaryFaces, ImpedanceOfSteelAtRest) {
  const double rho0 = 7810.0, c0 = 4578.0, G = 81.8e9;
  Simulation bulk(box_scene("[2, 2, 2]", "[1, 1, 1]", "{name: s, material: steel}"));
  Simulation strong(box_scene("[2, 2, 2]", "[1, 1, 1]",
                              "{name: s, material: steel, strength: {shear_modulus: 81.8e9, yield_stress: 1.0e9}}"));
  const double zp = rho0 * std::sqrt(c0 * c0 + 4.0 * G / (3.0 * rho0));
  EXPECT_NEAR(zp, 4.6154e7, 1e3);
  for (double z : bulk.boundary_faces().impedance) EXPECT_NEAR(z, rho0 * c0, 1e-6 * rho0 * c0);
  for (double z : strong.boundary_faces().impedance) EXPECT_NEAR(z, zp, 1e-6 * zp);
  // Rigid blocks: infinite impedance, no stress.
  Simulation rigid(box_scene("[1, 1]", "[1, 1]", "{name: r, rigid: true, density: 10.0}"));
  for (double z : rigid.boundary_faces().impedance) EXPECT_EQ(z, std::numeric_limits<double>::infinity());
}

// External face pressures equal to the gas pressure hold a free gas block in equilibrium; without them it
// expands. A face pressure on one face of a rigid block accelerates it at p A / m. Face velocities follow.
TEST(SolidBoundaryFaces, FacePressuresFromOutside) {
  for (bool held : {true, false}) {
    Simulation sim(box_scene("[4, 4, 4]", "[1, 1, 1]", kGas));
    const int nf = sim.boundary_faces().count;
    if (held) sim.set_face_pressures(std::vector<double>(nf, 1e5));
    const double e0 = sim.energy().total();
    solid_test::run_to(sim, 1e-4);
    double vmax = 0;
    for (double v : sim.state().v) vmax = std::max(vmax, std::abs(v));
    if (held) {
      EXPECT_LT(vmax, 1e-9);
    } else {
      EXPECT_GT(vmax, 1.0);
    }
    const auto e = sim.energy();
    EXPECT_NEAR(e.total() - e0 - e.boundary_work, 0.0, 1e-12 * e0);
  }
  Simulation r(box_scene("[2, 1]", "[2, 1]", "{name: r, rigid: true, density: 100.0}"));
  const BoundaryFaces& bf = r.boundary_faces();
  std::vector<double> p(bf.count, 0.0);
  for (int i = 0; i < bf.count; ++i)
    if (bf.normal[2 * i] < -0.5) p[i] = 1e5;  // the x_lower face
  r.set_face_pressures(p);
  for (int i = 0; i < 10; ++i) r.advance(1e-4);
  EXPECT_NEAR(r.rigid_bodies()[0].V[0], 1e5 / 200.0 * 1e-3, 1e-12);
  const BoundaryFaces& after = r.boundary_faces();
  for (int i = 0; i < after.count; ++i) EXPECT_NEAR(after.velocity[2 * i], 0.5, 1e-12);
  EXPECT_THROW(r.set_face_pressures({1.0}), std::invalid_argument);
}

// The coupler's interface velocity (paper section 8, step 1): the nodes of wetted faces take u_I along their
// faces' mean normal at the start of the next step; other nodes keep theirs; the kinetic-energy change is
// boundary work, so the energy balance still closes.
TEST(SolidBoundaryFaces, InterfaceVelocitySetsTheNodesOfWettedFaces) {
  SolidScene s = box_scene("[3, 2]", "[2, 1]", kGas);
  Simulation sim(s);
  const BoundaryFaces& bf = sim.boundary_faces();
  std::vector<double> u(bf.count, 0.0);
  std::vector<char> wet(bf.count, 0);
  std::vector<double> pressure(bf.count, 1e5);  // balances the gas: no acceleration from the stress
  for (int i = 0; i < bf.count; ++i)
    if (bf.normal[i * 2] > 0.99) {  // the +x side (x = 2) only
      wet[i] = 1;
      u[i] = 3.0;
    }
  sim.set_face_pressures(pressure);
  sim.set_face_normal_velocities(u, wet);
  const double e0 = sim.energy().total();
  sim.advance(1e-7);
  const State& st = sim.state();
  int moved = 0;
  for (int n = 0; n < sim.mesh().num_nodes; ++n) {
    const double x = st.x[2 * n], vx = st.v[2 * n], vy = st.v[2 * n + 1];
    if (std::abs(x - 2.0) < 1e-5) {
      EXPECT_NEAR(vx, 3.0, 1e-6) << n;  // only the tiny pressure-gradient change of one 0.1 us step
      ++moved;
    } else {
      EXPECT_NEAR(vx, 0.0, 1e-6) << n;
    }
    EXPECT_NEAR(vy, 0.0, 1e-6) << n;
  }
  EXPECT_EQ(moved, 3);  // the nodes of the +x side
  const auto e = sim.energy();
  EXPECT_GT(e.boundary_work, 0.0);
  EXPECT_NEAR(e.total() - e0 - e.boundary_work, 0.0, 1e-9 * e0);
  // Used once: the next step lets the nodes go.
  EXPECT_THROW(sim.set_face_normal_velocities(u, std::vector<char>(3, 1)), std::invalid_argument);
}

// A block translating at v with u_I = v . n on every face (what the coupler returns when the fluid moves with
// it) keeps its velocity at every node, corners included: the corner nodes meet both faces' conditions.
TEST(SolidBoundaryFaces, TranslatingBlockKeepsItsVelocityUnderItsOwnInterfaceVelocities) {
  for (int dim : {2, 3}) {
    SolidScene s = dim == 2 ? box_scene("[3, 2]", "[2, 1]", kGas) : box_scene("[3, 2, 2]", "[2, 1, 3]", kGas);
    Simulation sim(s);
    const double v[3] = {0.1, -0.2, 0.3};
    for (int n = 0; n < sim.mesh().num_nodes; ++n)
      for (int d = 0; d < dim; ++d) sim.state().v[static_cast<std::size_t>(n) * dim + d] = v[d];
    const BoundaryFaces& bf = sim.boundary_faces();
    std::vector<double> u(bf.count, 0.0), p(bf.count, 1e5);
    for (int f = 0; f < bf.count; ++f)
      for (int d = 0; d < dim; ++d) u[f] += v[d] * bf.normal[f * dim + d];
    sim.set_face_pressures(p);
    sim.set_face_normal_velocities(u, std::vector<char>(bf.count, 1));
    sim.advance(1e-7);
    double worst = 0;
    for (int n = 0; n < sim.mesh().num_nodes; ++n)
      for (int d = 0; d < dim; ++d)
        worst = std::max(worst, std::abs(sim.state().v[static_cast<std::size_t>(n) * dim + d] - v[d]));
    EXPECT_LT(worst, 1e-9) << dim << "D";
  }
}
