// Thin plates in the embedded boundary (fluid_solver/embedded/thin_body.h): bodies one background cell thick
// and thinner, with two-sided ghost states (side images) and blocked faces. Nothing may happen when a plate
// moves with the flow; a shock reflects off a fixed plate at the exact pressure and nothing passes it.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "common/exact/exact_riemann.h"
#include "fluid_test_utils.h"

namespace cosim::fluid::test {
namespace {

// A plate [0.3, 0.7] x [y0, y0 + thickness] moving diagonally with a uniform flow in a periodic box of N^2 cells,
// 200 steps: its walls cross every offset against the grid, through the cases of thin_body.h.
TEST(ThinPlates, PlateMovingWithTheFlowLeavesItUniform) {
  const int N = 32;
  const double h = 1.0 / N;
  for (double thickness : {1.0, 0.45})
    for (const char* order : {"1", "2"}) {
      char scene[1024];
      std::snprintf(scene, sizeof(scene), R"(
fluid:
  mesh: {cells: [%d, %d], lower: [0.0, 0.0], upper: [1.0, 1.0]}
  phases: [{name: gas, eos: {type: ideal_gas, gamma: 1.4}}]
  time: {end: 10.0, max_steps: 200}
  boundaries: {x_lower: periodic, x_upper: periodic, y_lower: periodic, y_upper: periodic}
  embedded:
    order: %s
    bodies:
      - {shape: box, lower: [0.3, %.17g], upper: [0.7, %.17g], velocity: [0.1, 0.13]}
  initial:
    state: {rho: 1.0, velocity: [0.1, 0.13], p: 1.0}
)",
                    N, N, order, 0.5 + 0.21 * h, 0.5 + (0.21 + thickness) * h);
      auto sim = run_scene(scene);
      ASSERT_EQ(sim->steps(), 200);
      const PhaseFields f = sim->phase_fields(0);
      const std::vector<double> kind = sim->embedded_categories();
      double du = 0, dp = 0, drho = 0;
      int flow = 0;
      for (std::size_t c = 0; c < f.p.size(); ++c) {
        if (kind[c] > 1) continue;
        ++flow;
        du = std::max({du, std::abs(f.velocity[3 * c] - 0.1), std::abs(f.velocity[3 * c + 1] - 0.13)});
        dp = std::max(dp, std::abs(f.p[c] - 1.0));
        drho = std::max(drho, std::abs(f.rho[c] - 1.0));
      }
      EXPECT_GT(flow, N * N - 3 * 14);
      EXPECT_LT(du, 1e-10) << thickness << " cells, order " << order;
      EXPECT_LT(dp, 1e-10) << thickness << " cells, order " << order;
      EXPECT_LT(drho, 1e-10) << thickness << " cells, order " << order;
    }
}

// A Mach 2 shock (Rankine-Hugoniot state behind it) runs into a fixed plate across the whole channel,
// [x0, x0 + thickness] with x0 = 0.5 + offset cells, 160 x 8 cells, slip walls at y = 0 and 0.05. At t = 0.2 the
// reflected shock is ~0.07 from the plate: the gas between is at rest at the pressure of the exact normal
// reflection (the symmetric Riemann problem of the post-shock state), measured 0.01..0.04 from the plate; behind
// the plate the gas at rest must not feel anything.
struct PlateRun {
  double reflected = 0, exact = 0, behind_dp = 0, behind_du = 0;
  std::vector<double> front;  // pressure of every flow cell ahead of the plate's front face
};

PlateRun shock_on_plate(double offset, double thickness, double angle_deg = 0.0) {
  const int NX = 160, NY = angle_deg == 0.0 ? 8 : 48;
  const double h = 1.0 / NX, gamma = 1.4, Ms = 2.0;
  const double p2 = 1.0 + 2 * gamma / (gamma + 1) * (Ms * Ms - 1);
  const double rho2 = (gamma + 1) * Ms * Ms / ((gamma - 1) * Ms * Ms + 2);
  const double u2 = Ms * std::sqrt(gamma) * (1.0 - 1.0 / rho2);
  const double x0 = 0.5 + offset * h, y1 = NY * h;
  // the plate as a polygon, tilted by angle_deg about its centre line's point at mid-height
  const double t = std::tan(angle_deg * std::numbers::pi / 180.0),
               w = thickness * h / std::cos(angle_deg * std::numbers::pi / 180.0);
  const double ym = 0.5 * y1, lo = -0.5, hi = y1 + 0.5;  // beyond the channel's walls
  char scene[2048];
  std::snprintf(scene, sizeof(scene), R"(
fluid:
  mesh: {cells: [%d, %d], lower: [0.0, 0.0], upper: [1.0, %.17g]}
  phases: [{name: gas, eos: {type: ideal_gas, gamma: 1.4}}]
  time: {end: 0.2}
  boundaries: {x_lower: transmissive, x_upper: transmissive}
  embedded:
    bodies:
      - {shape: polygon, vertices: [[%.17g, %.17g], [%.17g, %.17g], [%.17g, %.17g], [%.17g, %.17g]]}
  initial:
    state: {rho: 1.0, velocity: [0.0, 0.0], p: 1.0}
    regions:
      - box: {lower: [0.0, 0.0], upper: [0.2, %.17g]}
        state: {rho: %.17g, velocity: [%.17g, 0.0], p: %.17g}
)",
                NX, NY, y1, x0 + (lo - ym) * t, lo, x0 + w + (lo - ym) * t, lo, x0 + w + (hi - ym) * t, hi,
                x0 + (hi - ym) * t, hi, y1, rho2, u2, p2);
  auto sim = run_scene(scene);
  const PhaseFields f = sim->phase_fields(0);
  const std::vector<double> kind = sim->embedded_categories();
  PlateRun r;
  r.exact = exact::solve_star({rho2, u2, p2}, {gamma, 0}, {rho2, -u2, p2}, {gamma, 0}).p;
  double sum = 0;
  int n = 0;
  for (int j = 0; j < NY; ++j)
    for (int i = 0; i < NX; ++i) {
      const std::size_t c = static_cast<std::size_t>(j) * NX + i;
      if (kind[c] > 1) continue;
      const double x = (i + 0.5) * h, y = (j + 0.5) * h;
      const double front = x0 + (y - ym) * t - x;  // distance ahead of the plate's front face (along x)
      if (front > 0) r.front.push_back(f.p[c]);
      if (front > 0.01 && front < 0.04) {
        sum += f.p[c];
        ++n;
      }
      if (x > x0 + w + (y - ym) * t) {
        r.behind_dp = std::max(r.behind_dp, std::abs(f.p[c] - 1.0));
        r.behind_du = std::max(r.behind_du, std::hypot(f.velocity[3 * c], f.velocity[3 * c + 1]));
      }
    }
  r.reflected = n > 0 ? sum / n : 0.0;
  return r;
}

// The largest pressure difference ahead of the plates of two runs (infinite when their flow regions differ).
double front_difference(const PlateRun& a, const PlateRun& b) {
  if (a.front.size() != b.front.size()) return HUGE_VAL;
  double diff = 0;
  for (std::size_t c = 0; c < a.front.size(); ++c) diff = std::max(diff, std::abs(a.front[c] - b.front[c]));
  return diff;
}

TEST(ThinPlates, ShockReflectsOffAFixedThinPlateAndNothingPasses) {
  // one cell thick at offsets against the grid (0: both walls on grid lines; 0.5: on cell centres), and thinner
  for (const auto& [offset, thickness] : {std::pair{0.0, 1.0}, {0.3, 1.0}, {0.5, 1.0}, {0.77, 1.0}, {0.1, 0.4}}) {
    const PlateRun r = shock_on_plate(offset, thickness);
    std::printf("plate %.2f cells at offset %.2f: reflected p %.4f (exact %.4f, %+.2f%%), behind |dp| %.1e |u| %.1e\n",
                thickness, offset, r.reflected, r.exact, 100 * (r.reflected / r.exact - 1), r.behind_dp, r.behind_du);
    EXPECT_NEAR(r.reflected, r.exact, 0.01 * r.exact) << offset << " " << thickness;
    // ahead of the plate the flow is that of a thick wall at the same place: each side sees only its own wall
    const double diff = front_difference(r, shock_on_plate(offset, 3.0));
    EXPECT_LT(diff, 1e-12 * r.exact) << offset << " " << thickness;
    EXPECT_LT(r.behind_dp, 1e-10) << offset << " " << thickness;
    EXPECT_LT(r.behind_du, 1e-10) << offset << " " << thickness;
  }
}

// The same plate tilted by 20 degrees: its walls cut the grid lines of both directions, so cells along both see
// it two-sided; still nothing may pass.
TEST(ThinPlates, TiltedThinPlateLetsNothingThrough) {
  for (double thickness : {1.0, 0.5}) {
    const PlateRun r = shock_on_plate(0.3, thickness, 20.0);
    std::printf(
        "plate %.2f cells tilted 20 deg: reflected p %.4f (normal reflection %.4f), behind |dp| %.1e |u| %.1e\n",
        thickness, r.reflected, r.exact, r.behind_dp, r.behind_du);
    EXPECT_LT(r.behind_dp, 1e-10) << thickness;
    EXPECT_LT(r.behind_du, 1e-10) << thickness;
    const double diff = front_difference(r, shock_on_plate(0.3, 3.0, 20.0));
    std::printf("  ahead of it: max |p - p(thick wall)| = %.1e\n", diff);
    EXPECT_LT(diff, 1e-10 * r.exact) << thickness;  // round-off of the two closest-point computations
  }
}

}  // namespace
}  // namespace cosim::fluid::test
