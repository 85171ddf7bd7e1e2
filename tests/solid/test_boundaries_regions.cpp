// Boundaries and regions of a conforming gas mesh around a structure: the non-reflecting (absorbing) boundary,
// nodes clamped by a box inside the mesh, and circular block regions.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <cstdio>

#include "solid_solver/core/simulation.h"
#include "solid_test_util.h"

using namespace cosim::solid;

namespace {

// A gas column [0, 1] x [0, 0.01] m (rho 1.2, p 1e5, 400 elements along x) driven at x = 0 by a wall moving
// at 10 m/s: a weak compression (p0 + rho c u to first order) runs to x = 1 and meets `end`. At t = 5.5 ms
// (the front arrives at 1 / c = 2.9 ms; a reflection would have passed x = 0.3 by 5.0 ms and not yet reached the
// driven end) the mean pressure over x in [0.3, 0.7] is returned.
double pressure_after_the_end(const std::string& end) {
  SolidScene s = parse_solid_scene(fmt::format(R"(
solid:
  mesh: {{cells: [400, 1], lower: [0, 0], upper: [1, 0.01]}}
  blocks:
    - {{name: gas, eos: {{type: ideal_gas, gamma: 1.4}}, density: 1.2, initial: {{pressure: 1.0e5}}}}
  boundaries:
    - {{set: x_lower, type: velocity, vx: 10.0}}
    - {{set: y_lower, type: symmetry}}
    - {{set: y_upper, type: symmetry}}
    - {}
  time: {{end: 1.0}}
)",
                                               end));
  Simulation sim(s);
  solid_test::run_to(sim, 5.5e-3);
  double p = 0, w = 0;
  for (int e = 0; e < sim.mesh().num_elements; ++e) {
    const auto c = element_centroid(sim.mesh(), sim.state().x, e);
    if (c[0] > 0.3 && c[0] < 0.7) p += sim.state().p[e], w += 1;
  }
  return p / w;
}

}  // namespace

// The absorbing end lets the compression leave: the middle stays at the driven level, p0 + rho c u (+ the
// weak-shock correction); a free end at the ambient pressure sends back a rarefaction that takes it down to
// about p0, a symmetry plane a compression that doubles the jump.
TEST(SolidBoundaries, NonReflectingEndLetsAPlaneWaveLeave) {
  const double p0 = 1e5, rho = 1.2, c = std::sqrt(1.4 * p0 / rho), u = 10.0;
  // Driven level: the exact piston shock (Toro 4.7 solved for a given post-shock velocity).
  const double g = 1.4, a = (g + 1) / 4 * u / c;
  const double mach = a + std::sqrt(a * a + 1);
  const double driven = p0 * (1 + 2 * g / (g + 1) * (mach * mach - 1));
  const double absorbing = pressure_after_the_end("{set: x_upper, type: non_reflecting, value: 1.0e5}");
  const double free_end = pressure_after_the_end("{set: x_upper, type: pressure, value: 1.0e5}");
  const double wall = pressure_after_the_end("{set: x_upper, type: symmetry}");
  const double jump = driven - p0;
  std::printf(
      "[ measured ] pressure jump in the middle after the end (of the driven jump %.1f Pa): non-reflecting "
      "%.4f, free end %.4f, wall %.4f\n",
      jump, (absorbing - p0) / jump, (free_end - p0) / jump, (wall - p0) / jump);
  EXPECT_NEAR((absorbing - p0) / jump, 1.0, 0.02);
  EXPECT_LT((free_end - p0) / jump, 0.1);
  EXPECT_GT((wall - p0) / jump, 1.8);
}

// A box of nodes inside the mesh (a line across it) is clamped: those nodes stay put while the rest moves.
TEST(SolidBoundaries, NodeBoxClampsTheNodesInside) {
  SolidScene s = parse_solid_scene(R"(
solid:
  mesh: {cells: [10, 10], lower: [0, 0], upper: [1, 1]}
  blocks:
    - {name: gas, eos: {type: ideal_gas, gamma: 1.4}, density: 1.0, initial: {pressure: 1.0e5, velocity: [5.0, 3.0]}}
  boundaries:
    - {box: {lower: [0.3, 0.5], upper: [0.7, 0.5]}, type: fixed}
  time: {end: 1.0}
)");
  Simulation sim(s);
  solid_test::run_to(sim, 1e-4);
  int clamped = 0, moved = 0;
  for (int n = 0; n < sim.mesh().num_nodes; ++n) {
    const double x0 = sim.mesh().x0[2 * n], y0 = sim.mesh().x0[2 * n + 1];
    const double dx = std::hypot(sim.state().x[2 * n] - x0, sim.state().x[2 * n + 1] - y0);
    const bool in = x0 > 0.3 - 1e-9 && x0 < 0.7 + 1e-9 && std::abs(y0 - 0.5) < 1e-9;
    if (in) {
      ++clamped;
      EXPECT_EQ(dx, 0.0) << n;
    } else if (dx > 1e-4) {
      ++moved;
    }
  }
  EXPECT_EQ(clamped, 5);
  EXPECT_GT(moved, 100);
}

// Circular regions take the elements whose centroid lies in the circle; a later region overrides an earlier one.
TEST(SolidRegions, CircleRegionTakesTheElementsInside) {
  SolidScene s = parse_solid_scene(R"(
solid:
  mesh:
    cells: [40, 40]
    lower: [0, 0]
    upper: [1, 1]
    regions:
      - {block: hot, center: [0.5, 0.5], radius: 0.25}
      - {block: core, lower: [0.45, 0.45], upper: [0.55, 0.55]}
  blocks:
    - {name: cold, eos: {type: ideal_gas, gamma: 1.4}, density: 1.0, initial: {pressure: 1.0}}
    - {name: hot, eos: {type: ideal_gas, gamma: 1.4}, density: 1.0, initial: {pressure: 10.0}}
    - {name: core, eos: {type: ideal_gas, gamma: 1.4}, density: 1.0, initial: {pressure: 100.0}}
  time: {end: 1.0}
)");
  Simulation sim(s);
  const auto& m = sim.mesh();
  const double area = 1.0 / 1600;
  const double hot = (m.block_range[1][1] - m.block_range[1][0]) * area;
  const double core = (m.block_range[2][1] - m.block_range[2][0]) * area;
  EXPECT_EQ(m.block_range[2][1] - m.block_range[2][0], 16);  // 4 x 4 elements
  EXPECT_NEAR(hot + core, M_PI * 0.25 * 0.25, 0.02);         // the staircase of the circle
  for (int e = 0; e < m.num_elements; ++e) {
    const auto c = element_centroid(m, m.x0, e);
    const double r = std::hypot(c[0] - 0.5, c[1] - 0.5);
    if (m.element_block[e] == 1) {
      EXPECT_LE(r, 0.25);
    } else if (m.element_block[e] == 0) {
      EXPECT_GT(r, 0.25);
    }
  }
}

// Bad input: a box and a set together, a box with a pressure, a box holding no node, a region with both shapes.
TEST(SolidBoundaries, BadBoxesAndRegionsAreRefusedByName) {
  const std::string head = R"(
solid:
  mesh: {cells: [4, 4], lower: [0, 0], upper: [1, 1]}
  blocks:
    - {name: gas, eos: {type: ideal_gas, gamma: 1.4}, density: 1.0, initial: {pressure: 1.0}}
  time: {end: 1.0}
  boundaries:
)";
  auto error = [&](const std::string& bc) {
    try {
      Simulation sim(parse_solid_scene(head + "    - " + bc + "\n"));
    } catch (const std::exception& e) { return std::string(e.what()); }
    return std::string();
  };
  EXPECT_NE(error("{set: x_lower, box: {lower: [0, 0], upper: [1, 0]}, type: fixed}").find("either set"),
            std::string::npos);
  EXPECT_NE(error("{box: {lower: [0, 0], upper: [1, 0]}, type: pressure, value: 1}").find("fixed or velocity"),
            std::string::npos);
  EXPECT_NE(error("{box: {lower: [0.1, 0.1], upper: [0.2, 0.2]}, type: fixed}").find("holds no node"),
            std::string::npos);
  EXPECT_EQ(error("{set: x_lower, type: non_reflecting, value: 1.0}"), "");
}
