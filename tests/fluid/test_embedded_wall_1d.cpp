// The flow side of the embedded boundary with a hand-built planar wall on a cell face: it must
// reproduce the solver's own reflective boundary, and a moving wall the exact piston shock.
#include <gtest/gtest.h>

#include "common/exact/exact_riemann.h"
#include "fluid_solver/core/grid.h"
#include "fluid_test_utils.h"

namespace cosim::fluid::test {
namespace {

// Solid for x > x_wall, moving with velocity w: the 1D version of the geometry (categories of
// paper Table 1, mirror image points interpolated from flow cells only, the wall face with its d).
EmbeddedState planar_wall_1d(const FluidScene& s, double x_wall, double w) {
  Grid<1> g(s.cells, s.lower, s.upper);
  const double dx = g.dx[0];
  auto xc = [&](int i) { return g.center(0, i); };
  EmbeddedState e;
  e.active = true;
  e.kind.assign(g.total, static_cast<std::uint8_t>(CellKind::Fluid));
  e.max_wall_speed = std::abs(w);
  int iw = 0;  // first cell whose centre is in the solid
  while (xc(iw) <= x_wall) ++iw;
  if (x_wall < xc(iw) - 0.5 * dx) e.kind[g.index(iw - 1)] = static_cast<std::uint8_t>(CellKind::FluidCut);
  for (int i = iw; i < g.n[0] + Grid<1>::NG; ++i) {
    const std::size_t c = g.index(i);
    if (i >= iw + 2) {
      e.kind[c] = static_cast<std::uint8_t>(CellKind::Solid);
      continue;
    }
    e.kind[c] = static_cast<std::uint8_t>(i == iw && x_wall > xc(iw) - 0.5 * dx ? CellKind::SolidCut : CellKind::Ghost);
    GhostRecord gr;
    gr.cell = c;
    gr.normal = {-1, 0, 0};
    gr.wall_velocity = {w, 0, 0};
    gr.distance = xc(i) - x_wall;
    gr.image_distance = 2 * gr.distance;
    const double xip = x_wall - gr.distance;
    const int j = static_cast<int>(std::floor((xip - s.lower[0]) / dx - 0.5));  // xc(j) <= xip < xc(j+1)
    if (j + 1 < iw) {  // both neighbours are flow cells: linear interpolation
      const double t = (xip - xc(j)) / dx;
      gr.stencil_size = 2;
      gr.stencil = {g.index(j), g.index(j + 1)};
      gr.weights = {1 - t, t};
    } else {  // the image point lies beyond the last flow centre: use that cell alone
      gr.stencil_size = 1;
      gr.stencil[0] = g.index(iw - 1);
      gr.weights[0] = 1.0;
    }
    e.ghosts.push_back(gr);
  }
  WallFace f;
  f.fluid_cell = g.index(iw - 1);
  f.fluid_cell2 = g.index(iw - 2);
  f.fluid_cell3 = g.index(iw - 3);
  f.fluid_cell4 = g.index(iw - 4);
  f.solid_cell = g.index(iw);
  f.solid_on_high_side = true;
  f.normal = {-1, 0, 0};
  f.wall_velocity = {w, 0, 0};
  f.d = (x_wall - xc(iw - 1)) / dx;
  e.faces[0].push_back(f);
  return e;
}

const char* kScene = R"(
fluid:
  mesh: {cells: [400], lower: [0.0], upper: [1.0]}
  phases: [{name: gas, eos: {type: ideal_gas, gamma: 1.4}}]
  time: {end: 0.3}
  initial:
    state: {rho: 1.0, velocity: [1.0], p: 1.0}
)";

TEST(EmbeddedWall1D, StaticWallOnAFaceEqualsReflectiveBoundary) {
  for (bool second : {false, true}) {
    // Reference: domain [0, 0.75] with a reflective wall at x = 0.75.
    auto ref =
        run_scene(kScene, {"fluid.mesh.cells=[300]", "fluid.mesh.upper=[0.75]", "fluid.boundaries.x_upper=wall"});
    FluidScene s = parse_fluid_scene(kScene);
    auto sim = make_simulation(s);
    sim->set_embedded(planar_wall_1d(s, 0.75, 0.0), second);
    advance_to(*sim, s.t_end);
    PhaseFields a = sim->phase_fields(0), b = ref->phase_fields(0);
    EXPECT_EQ(sim->steps(), ref->steps());
    double err = 0;
    for (int i = 0; i < 300; ++i)
      err = std::max({err, std::abs(a.rho[i] - b.rho[i]), std::abs(a.p[i] - b.p[i]),
                      std::abs(a.velocity[3 * i] - b.velocity[3 * i])});
    EXPECT_LT(err, 1e-12) << (second ? "second order" : "first order");
  }
}

// A wall moving at constant speed: into gas at rest it drives a shock, away from it a rarefaction;
// the gas between wave and wall takes the exact star state of the symmetric Riemann problem.
TEST(EmbeddedWall1D, MovingPistonDrivesExactShockAndRarefaction) {
  const char* scene = R"(
fluid:
  mesh: {cells: [400], lower: [0.0], upper: [1.0]}
  phases: [{name: gas, eos: {type: ideal_gas, gamma: 1.4}}]
  time: {end: 0.25}
  initial:
    state: {rho: 1.0, velocity: [0.0], p: 1.0}
)";
  for (double w : {-0.8, -0.3, 0.3}) {
    for (bool second : {false, true}) {
      FluidScene s = parse_fluid_scene(scene);
      auto sim = make_simulation(s);
      double x_wall = 0.8023;  // not on a face
      while (sim->time() < s.t_end - 1e-12) {
        sim->set_embedded(planar_wall_1d(s, x_wall, w), second);
        const double dt = std::min(sim->stable_dt(), s.t_end - sim->time());
        sim->advance(dt);
        x_wall += w * dt;
      }
      const exact::Star star = exact::solve_star({1, 0, 1}, {1.4, 0}, {1, 2 * w, 1}, {1.4, 0});
      // Probe halfway between the wave and the wall.
      exact::RiemannSolution ex({1, 0, 1}, {1.4, 0}, {1, 2 * w, 1}, {1.4, 0});  // mirror state
      const double x_wave = 0.8023 + s.t_end * ex.left_tail();                  // shock, or the rarefaction's tail
      const double x_probe = 0.5 * (x_wave + x_wall);
      PhaseFields f = sim->phase_fields(0);
      const int i = static_cast<int>(x_probe * 400);
      std::printf("wall speed %+.1f (%s order): p %.5f (exact %.5f), u %.5f (exact %.5f), rho %.5f (exact %.5f)\n", w,
                  second ? "2nd" : "1st", f.p[i], star.p, f.velocity[3 * i], w, f.rho[i], star.rho_left);
      EXPECT_NEAR(f.p[i], star.p, 0.01 * star.p) << w << second;
      EXPECT_NEAR(f.velocity[3 * i], w, 0.01 * std::abs(w)) << w << second;
      EXPECT_NEAR(f.rho[i], star.rho_left, 0.01 * star.rho_left) << w << second;
    }
  }
}

}  // namespace
}  // namespace cosim::fluid::test
