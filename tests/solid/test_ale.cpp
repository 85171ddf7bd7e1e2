// ALE gas blocks (solid_solver/ale/): swept volumes, the rezone, and the conservative remap, against what
// they must give: exact volume changes, a uniform flow that stays uniform, conservation in a closed box, and
// the Sod shock tube on an ALE mesh against the exact solution.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <cstdio>

#include "common/exact/exact_riemann.h"
#include "solid_solver/ale/remap.h"
#include "solid_solver/core/simulation.h"
#include "solid_solver/kinematics/element_geometry.h"
#include "solid_solver/mesh/element_faces.h"
#include "solid_test_util.h"

using namespace cosim::solid;

// The swept volumes of an element's faces add up to its volume change, for random node moves of up to 30% of
// a cell (quads and hexes): the remap's mass is then exactly what the new volumes hold.
TEST(SolidAle, SweptVolumesAddUpToTheVolumeChange) {
  for (int dim : {2, 3}) {
    const Mesh m = make_box_mesh(dim, {4, 3, 2}, {0, 0, 0}, {1, 1, 1});
    std::vector<double> xo = m.x0, xn = m.x0;
    for (std::size_t i = 0; i < xo.size(); ++i) {
      xo[i] += 0.07 * solid_test::hash_unit(static_cast<int>(i), 1);
      xn[i] += 0.07 * solid_test::hash_unit(static_cast<int>(i), 2);
    }
    double worst = 0;
    for (int e = 0; e < m.num_elements; ++e) {
      double sum = 0;
      for (int f = 0; f < faces_per_element(dim); ++f) sum += swept_volume(dim, element_face_nodes(m, e, f), xo, xn);
      const double change = element_volume(m, xn, e) - element_volume(m, xo, e);
      worst = std::max(worst, std::abs(sum - change) / element_volume(m, xo, e));
    }
    std::printf("[ measured ] %dD: swept volumes vs volume change, worst relative difference %.2e\n", dim, worst);
    EXPECT_LT(worst, 1e-13);
  }
}

namespace {
// A gas box [0, 1]^D, cells^D elements, ALE on the whole block, with the given boundary lines and initial state.
Simulation gas_box(int dim, int cells, const std::string& boundaries, const std::string& initial,
                   const std::string& regions = "", const std::string& extra_blocks = "") {
  const std::string c = dim == 2 ? fmt::format("[{0}, {0}]", cells) : fmt::format("[{0}, {0}, {0}]", cells);
  const std::string lo = dim == 2 ? "[0, 0]" : "[0, 0, 0]", hi = dim == 2 ? "[1, 1]" : "[1, 1, 1]";
  return Simulation(parse_solid_scene(fmt::format(R"(
solid:
  mesh: {{cells: {}, lower: {}, upper: {}{}}}
  blocks:
    - {{name: gas, eos: {{type: ideal_gas, gamma: 1.4}}, density: 1.0, initial: {}}}{}
  ale: {{blocks: [gas{}]}}
  boundaries:
{}
  time: {{end: 1.0}}
)",
                                                  c, lo, hi, regions, initial, extra_blocks,
                                                  extra_blocks.empty() ? "" : ", hot", boundaries)));
}
}  // namespace

// A uniform flow through an Eulerian (ALE) gas mesh whose exterior holds the flow's own pressure: the inflow
// faces take the element's own state, so nothing may change (to round-off), in 2D and 3D.
TEST(SolidAle, UniformFlowStaysUniform) {
  for (int dim : {2, 3}) {
    std::string bc;
    for (const char* s : {"x_lower", "x_upper", "y_lower", "y_upper", "z_lower", "z_upper"})
      if (dim == 3 || s[0] != 'z') bc += fmt::format("    - {{set: {}, type: pressure, value: 1.0e5}}\n", s);
    const std::string v = dim == 2 ? "[30.0, -20.0]" : "[30.0, -20.0, 10.0]";
    Simulation sim = gas_box(dim, dim == 2 ? 8 : 4, bc, "{pressure: 1.0e5, velocity: " + v + "}");
    for (int k = 0; k < 50; ++k) sim.advance(0.5 * sim.stable_dt());
    const State& st = sim.state();
    double worst = 0, moved = 0;
    for (int e = 0; e < sim.mesh().num_elements; ++e) {
      worst = std::max({worst, std::abs(st.emass[e] / st.vol[e] - 1.0), std::abs(st.p[e] / 1e5 - 1.0)});
    }
    const double vel[3] = {30, -20, 10};
    for (int n = 0; n < sim.mesh().num_nodes; ++n)
      for (int d = 0; d < dim; ++d) {
        worst = std::max(worst, std::abs(st.v[n * dim + d] - vel[d]) / 30.0);
        moved = std::max(moved, std::abs(st.x[n * dim + d] - sim.mesh().x0[n * dim + d]));
      }
    std::printf(
        "[ measured ] %dD uniform flow through an ALE mesh, 50 steps: worst relative change %.2e, node "
        "moved %.2e m\n",
        dim, worst, moved);
    EXPECT_LT(worst, 1e-12);
    EXPECT_LT(moved, 1e-12);                // the mesh stays the initial one (Eulerian)
    EXPECT_GT(sim.ale_flux().mass, -1e-9);  // as much comes in as goes out
    EXPECT_LT(std::abs(sim.ale_flux().mass), 1e-9);
  }
}

// A blast in a closed box (symmetry walls; a hot disc of 100x the pressure) on an ALE mesh: mass conserved to
// round-off, total energy to the kinetic energy the remap could not return (measured), the mesh Eulerian.
TEST(SolidAle, ClosedBoxBlastConservesMassAndEnergy) {
  std::string bc;
  for (const char* s : {"x_lower", "x_upper", "y_lower", "y_upper"})
    bc += fmt::format("    - {{set: {}, type: symmetry}}\n", s);
  Simulation sim =
      gas_box(2, 40, bc, "{pressure: 1.0e5}", ", regions: [{block: hot, center: [0.4, 0.5], radius: 0.15}]",
              "\n    - {name: hot, eos: {type: ideal_gas, gamma: 1.4}, density: 1.0, initial: {pressure: 1.0e7}}");
  double m0 = 0;
  for (double m : sim.state().emass) m0 += m;
  const double e0 = sim.energy().total();
  solid_test::run_to(sim, 2e-3);
  double m1 = 0;
  for (double m : sim.state().emass) m1 += m;
  const double e1 = sim.energy().total();
  std::printf(
      "[ measured ] closed-box blast on an ALE mesh to t = 2 ms (%ld steps): mass error %.2e, energy error "
      "%.2e (relative), kinetic energy turned into heat %.3e of the total\n",
      sim.steps(), (m1 - m0) / m0, (e1 - e0) / e0, sim.ale_flux().kinetic_to_internal / e0);
  EXPECT_LT(std::abs(m1 - m0) / m0, 1e-13);
  EXPECT_LT(std::abs(e1 - e0) / e0, 2e-3);
  EXPECT_GT(sim.ale_flux().kinetic_to_internal, 0.0);
}

namespace {
// Sod (rho, u, p) = (1, 0, 1) | (0.125, 0, 0.1) at x = 0.5 on [0, 1] x [0, 0.01], n elements, at t = 0.2; L1
// error of the density at the element centres.
double sod_ale_error(int n, bool ale) {
  SolidScene s = parse_solid_scene(fmt::format(R"(
solid:
  mesh:
    cells: [{}, 1]
    lower: [0, 0]
    upper: [1, 0.01]
    regions: [{{block: right, lower: [0.5, -1], upper: [2, 1]}}]
  blocks:
    - {{name: left, eos: {{type: ideal_gas, gamma: 1.4}}, density: 1.0, initial: {{pressure: 1.0}}}}
    - {{name: right, eos: {{type: ideal_gas, gamma: 1.4}}, density: 0.125, initial: {{pressure: 0.1}}}}
  {}
  boundaries:
    - {{set: x_lower, type: symmetry}}
    - {{set: x_upper, type: symmetry}}
    - {{set: y_lower, type: symmetry}}
    - {{set: y_upper, type: symmetry}}
  time: {{end: 1.0}}
)",
                                               n, ale ? "ale: {blocks: [left, right]}" : ""));
  Simulation sim(s);
  solid_test::run_to(sim, 0.2);
  const cosim::exact::RiemannSolution ex({1.0, 0.0, 1.0}, {1.4, 0.0}, {0.125, 0.0, 0.1}, {1.4, 0.0});
  double err = 0, w = 0;
  for (int e = 0; e < sim.mesh().num_elements; ++e) {
    const auto c = element_centroid(sim.mesh(), sim.state().x, e);
    const double V = sim.state().vol[e];
    err += V * std::abs(sim.state().emass[e] / V - ex.sample((c[0] - 0.5) / 0.2).rho);
    w += V;
  }
  return err / w;
}
}  // namespace

// The Sod shock tube on an ALE (Eulerian) gas mesh: first-order convergence to the exact solution. The ALE
// error sits within a few times the Lagrangian mesh's (which keeps the contact sharp).
TEST(SolidAle, SodShockTubeConverges) {
  const double a = sod_ale_error(100, true), b = sod_ale_error(200, true);
  const double lag = sod_ale_error(200, false);
  std::printf("[ measured ] Sod on an ALE mesh: L1(rho) %.3e (100) %.3e (200), order %.2f; Lagrangian (200) %.3e\n", a,
              b, std::log2(a / b), lag);
  EXPECT_LT(b, 0.012);
  EXPECT_GT(std::log2(a / b), 0.6);
  EXPECT_LT(b, 4 * lag);
}
