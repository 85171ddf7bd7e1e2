// The flow side of the embedded boundary with a hand-built planar wall on a cell face: it must
// reproduce the solver's own reflective boundary, and a moving wall the exact piston shock.
#include <gtest/gtest.h>

#include "common/exact/exact_riemann.h"
#include "fluid_solver/core/grid.h"
#include "fluid_test_utils.h"

namespace cosim::fluid::test {
namespace {

// Solid for x > x_wall (x_wall on a cell face of the 1D grid), moving with velocity w.
EmbeddedState planar_wall_1d(const FluidScene& s, double x_wall, double w) {
  Grid<1> g(s.cells, s.lower, s.upper);
  EmbeddedState e;
  e.active = true;
  e.kind.assign(g.total, static_cast<std::uint8_t>(CellKind::Fluid));
  e.max_wall_speed = std::abs(w);
  const int iw = static_cast<int>(std::lround((x_wall - s.lower[0]) / g.dx[0]));  // first solid cell
  for (int i = iw; i < g.n[0] + Grid<1>::NG; ++i) {
    const std::size_t c = g.index(i);
    const int m = 2 * iw - 1 - i;  // mirror cell
    if (i < iw + 2) {
      e.kind[c] = static_cast<std::uint8_t>(CellKind::Ghost);
      GhostRecord gr;
      gr.cell = c;
      gr.normal = {-1, 0, 0};
      gr.wall_velocity = {w, 0, 0};
      gr.distance = (i - iw + 0.5) * g.dx[0];
      gr.image_distance = 2 * gr.distance;
      gr.stencil_size = 1;
      gr.stencil[0] = g.index(m);
      gr.weights[0] = 1.0;
      e.ghosts.push_back(gr);
    } else {
      e.kind[c] = static_cast<std::uint8_t>(CellKind::Solid);
    }
  }
  WallFace f;
  f.fluid_cell = g.index(iw - 1);
  f.fluid_cell2 = g.index(iw - 2);
  f.solid_cell = g.index(iw);
  f.solid_on_high_side = true;
  f.normal = {-1, 0, 0};
  f.wall_velocity = {w, 0, 0};
  f.d = 0.5;
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
    auto ref = run_scene(kScene, {"fluid.mesh.cells=[300]", "fluid.mesh.upper=[0.75]", "fluid.boundaries.x_upper=wall"});
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

}  // namespace
}  // namespace cosim::fluid::test
