// The embedded boundary in the flow solver, driven by the scene's bodies: advection
// with the flow (paper 9.2), walls at an angle, reflected shocks, moving pistons.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "common/exact/exact_riemann.h"
#include "fluid_test_utils.h"
#include "tests/support/scratch_dir.h"

namespace cosim::fluid::test {
namespace {

std::vector<double> categories(const FluidSimulation& sim) { return sim.embedded_categories(); }

// Paper 9.2: a body moving diagonally with the fluid's velocity, 13 x 13 cells, 200 cycles.
TEST(EmbeddedFlow, AdvectionWithTheFlowStaysUniform) {
  for (const char* order : {"1", "2"}) {
    FluidScene s = load_fluid_scene(std::string(COSIM_SOURCE_DIR) + "/configs/embedded_advection.yaml",
                                    {std::string("fluid.embedded.order=") + order});
    auto sim = make_simulation(s);
    advance_to(*sim, s.t_end);
    EXPECT_EQ(sim->steps(), 200);
    PhaseFields f = sim->phase_fields(0);
    auto kind = categories(*sim);
    double du = 0, dp = 0;
    int flow = 0;
    for (std::size_t c = 0; c < f.p.size(); ++c) {
      if (kind[c] > 1) continue;
      ++flow;
      du = std::max({du, std::abs(f.velocity[3 * c] - 0.1) / 0.1, std::abs(f.velocity[3 * c + 1] - 0.1) / 0.1});
      dp = std::max(dp, std::abs(f.p[c] - 1.0));
    }
    EXPECT_GT(flow, 100);
    EXPECT_LT(du, 1e-10) << order;
    EXPECT_LT(dp, 1e-10) << order;
  }
}

// The wall line passes through (0, kWallY0), off the cell centres and faces.
constexpr double kWallY0 = 0.3037;

// Solid below the line through (0, y0) at angle theta (a long rotated polygon), flow state STATE.
std::string angled_wall_scene(double theta_deg, int n, const std::string& state, double t_end,
                              const std::string& extra = "") {
  const double t = std::tan(theta_deg * std::numbers::pi / 180.0), y0 = kWallY0;
  char buf[2048];
  std::snprintf(buf, sizeof(buf), R"(
fluid:
  mesh: {cells: [%d, %d], lower: [0.0, 0.0], upper: [1.0, 1.0]}
  phases: [{name: gas, eos: {type: ideal_gas, gamma: 1.4}}]
  time: {end: %g}
  embedded:
    bodies:
      - {shape: polygon, vertices: [[-1.0, %.17g], [-1.0, -3.0], [3.0, -3.0], [3.0, %.17g]]}
  initial:
    state: %s
%s)",
                n, n, t_end, y0 - t, y0 + 3 * t, state.c_str(), extra.c_str());
  return buf;
}

// The time step comes from the flow cells only: whatever the cells inside a body hold (here a state 100x
// hotter and fast, set by an initial region that the body covers) does not change it.
TEST(EmbeddedFlow, TimeStepIgnoresTheStatesInsideBodies) {
  const std::string scene = R"(
fluid:
  mesh: {cells: [40, 40], lower: [0.0, 0.0], upper: [1.0, 1.0]}
  phases: [{name: gas, eos: {type: ideal_gas, gamma: 1.4}}]
  time: {end: 0.1}
  embedded:
    bodies:
      - {shape: box, lower: [0.3, 0.3], upper: [0.7, 0.7]}
  initial:
    state: {rho: 1.0, velocity: [0.5, 0.0], p: 1.0}
)";
  const std::string hot = scene + R"(    regions:
      - box: {lower: [0.4, 0.4], upper: [0.6, 0.6]}
        state: {rho: 1.0, velocity: [30.0, 0.0], p: 100.0}
)";
  auto plain = make_simulation(parse_fluid_scene(scene));
  auto covered = make_simulation(parse_fluid_scene(hot));
  ASSERT_GT(plain->stable_dt(), 0.0);
  EXPECT_EQ(covered->stable_dt(), plain->stable_dt());
  // A region reaching into the flow does change it.
  auto open =
      make_simulation(parse_fluid_scene(scene + "    regions:\n      - box: {lower: [0.1, 0.1], upper: [0.2, 0.2]}\n   "
                                                "     state: {rho: 1.0, velocity: [30.0, 0.0], p: 100.0}\n"));
  EXPECT_LT(open->stable_dt(), 0.2 * plain->stable_dt());
}

// A uniform flow parallel to a wall at 30 degrees to the grid stays (nearly) uniform.
TEST(EmbeddedFlow, UniformFlowParallelToAnAngledWall) {
  const double th = 30 * std::numbers::pi / 180.0, U = 0.5;
  char state[256];
  std::snprintf(state, sizeof(state), "{rho: 1.0, velocity: [%.17g, %.17g], p: 1.0}", U * std::cos(th),
                U * std::sin(th));
  for (const char* order : {"1", "2"}) {
    auto sim = run_scene(angled_wall_scene(30, 64, state, 0.5), {std::string("fluid.embedded.order=") + order});
    PhaseFields f = sim->phase_fields(0);
    auto kind = categories(*sim);
    double dmax = 0, dmean = 0;
    int n = 0;
    for (std::size_t c = 0; c < f.p.size(); ++c) {
      if (kind[c] > 1) continue;
      const double du = std::hypot(f.velocity[3 * c] - U * std::cos(th), f.velocity[3 * c + 1] - U * std::sin(th));
      dmax = std::max(dmax, du / U);
      dmean += du / U;
      ++n;
    }
    std::printf("order %s: uniform flow along a 30-degree wall: max |du|/U = %.3e, mean %.3e\n", order, dmax,
                dmean / n);
    EXPECT_LT(dmax, 0.05) << order;
    EXPECT_LT(dmean / n, 2e-3) << order;
  }
}

// Gas moving into a wall at 0, 30 and 45 degrees: the reflected shock leaves the gas at rest at
// the pressure of the 1D normal reflection (exact symmetric Riemann problem).
TEST(EmbeddedFlow, ReflectedShockOffAngledWalls) {
  const exact::Star star = exact::solve_star({1, 0.5, 1}, {1.4, 0}, {1, -0.5, 1}, {1.4, 0});
  for (double deg : {0.0, 30.0, 45.0}) {
    const double th = deg * std::numbers::pi / 180.0;
    // normal into the fluid: (-sin, cos); the gas moves against it.
    const double nx = -std::sin(th), ny = std::cos(th);
    char state[256];
    std::snprintf(state, sizeof(state), "{rho: 1.0, velocity: [%.17g, %.17g], p: 1.0}", 0.5 * nx, -0.5 * ny);
    std::snprintf(state, sizeof(state), "{rho: 1.0, velocity: [%.17g, %.17g], p: 1.0}", -0.5 * nx, -0.5 * ny);
    const int N = 160;
    auto sim = run_scene(
        angled_wall_scene(deg, N, state, 0.12, "  boundaries: {x_lower: transmissive, x_upper: transmissive}\n"));
    PhaseFields f = sim->phase_fields(0);
    auto kind = categories(*sim);
    // Average over flow cells 0.01..0.05 from the wall (the reflected shock is at ~0.12), within
    // 0.12 along the wall of the middle of its part inside the domain: waves from where the wall
    // meets the domain boundary (speed ~1.3) cannot reach there by t = 0.12.
    const double tt = std::tan(th);
    const double x_end = std::min(1.0, (1.0 - kWallY0) / std::max(tt, 1e-12));
    const double xm = 0.5 * x_end, ym = kWallY0 + xm * tt;
    double psum = 0;
    int n = 0;
    for (int j = 0; j < N; ++j)
      for (int i = 0; i < N; ++i) {
        const std::size_t c = static_cast<std::size_t>(j) * N + i;
        if (kind[c] > 1) continue;
        const double x = (i + 0.5) / N, y = (j + 0.5) / N;
        const double dist = (y - kWallY0 - x * tt) * std::cos(th);
        const double along = (x - xm) * std::cos(th) + (y - ym) * std::sin(th);
        if (dist < 0.01 || dist > 0.05 || std::abs(along) > 0.12) continue;
        psum += f.p[c];
        ++n;
      }
    ASSERT_GT(n, 10);
    std::printf("wall at %2.0f deg: reflected pressure %.4f (exact %.4f, %d cells)\n", deg, psum / n, star.p, n);
    EXPECT_NEAR(psum / n, star.p, 0.005 * star.p) << deg;
  }
}

// A wall at angle deg moving into gas at rest at speed w along its normal (a piston), measured in a
// strip 0.2 wide along the wall around x = 0.35, against the exact solution (uniform p* between the
// wall and the shock, gas at rest ahead):
// - l1: mean |p - p_exact| from the wall to 0.1 beyond the shock (the smeared shock included);
// - shock_offset: the shock's position from the equal-area rule, minus the exact one, in cells;
// - near_wall: mean |p - p*| / p* over the half of the shocked gas next to the wall.
struct PistonErrors {
  double l1 = 0, shock_offset = 0, near_wall = 0;
};

PistonErrors piston_errors(int N, int order, double w, double t_end, double deg) {
  const double th = deg * std::numbers::pi / 180.0, nx = -std::sin(th), ny = std::cos(th);
  char extra[256];
  std::snprintf(extra, sizeof(extra), "  boundaries: {x_lower: transmissive, x_upper: transmissive}\n");
  std::string scene = angled_wall_scene(deg, N, "{rho: 1.0, velocity: [0.0, 0.0], p: 1.0}", t_end, extra);
  char vel[128];
  std::snprintf(vel, sizeof(vel), "]], velocity: [%.17g, %.17g]}", w * nx, w * ny);
  scene.replace(scene.find("]]}"), 3, vel);
  auto sim = run_scene(scene, {"fluid.embedded.order=" + std::to_string(order)});
  exact::RiemannSolution ex({1, 0, 1}, {1.4, 0}, {1, -2 * w, 1}, {1.4, 0});  // gas | mirror, in the wall frame
  const double shock = -ex.left_tail() * t_end;  // distance the shock travelled from the initial wall
  const double wall = w * t_end, half = 0.5 * (wall + shock), far = shock + 0.1;
  const double p_star = ex.star().p;
  PhaseFields f = sim->phase_fields(0);
  auto kind = categories(*sim);
  const double tt = std::tan(th), xm = 0.35, ym = kWallY0 + xm * tt;
  PistonErrors e;
  double excess = 0;
  int n_all = 0, n_near = 0, n_ahead = 0;
  for (int j = 0; j < N; ++j)
    for (int i = 0; i < N; ++i) {
      const std::size_t c = static_cast<std::size_t>(j) * N + i;
      if (kind[c] > 1) continue;
      const double x = (i + 0.5) / N, y = (j + 0.5) / N;
      const double dist = (y - kWallY0 - x * tt) * std::cos(th);  // from the initial wall
      const double along = (x - xm) * std::cos(th) + (y - ym) * std::sin(th);
      if (std::abs(along) > 0.1 || dist > far) continue;
      e.l1 += std::abs(f.p[c] - (dist < shock ? p_star : 1.0));
      ++n_all;
      if (dist < half) {
        e.near_wall += std::abs(f.p[c] - p_star) / p_star;
        ++n_near;
      } else {
        excess += (f.p[c] - 1.0) / (p_star - 1.0);
        ++n_ahead;
      }
    }
  EXPECT_GT(n_near, 4);
  e.l1 /= n_all;
  e.near_wall /= n_near;
  e.shock_offset = (half + (far - half) * excess / n_ahead - shock) * N;
  return e;
}

// Constant-speed pistons into gas at rest (weak: w = 0.4, shock Mach 1.22; strong: w = 2, Mach 2.4),
// along the grid and at 30 degrees, first- and second-order boundary. A shock's error is its smearing:
// the L1 error converges at first order whatever the boundary, and the boundary's order cannot show
// in it. What the boundary controls is the state it drives and where the shock is: the post-shock
// state next to the wall within 0.1% at 160 cells and the shock within a cell of the exact one at
// every resolution, with either treatment. The impulsive start is a discontinuity at the wall that
// the d-weighted face states (eq. 23) extrapolate as if it were smooth: they push slightly less gas
// in the first steps, and the strong shock lags 0.4-0.6 cells (0.1-0.3 with first-order faces).
// The boundary's order shows on smooth flow: test_embedded_smooth_piston.cpp.
TEST(EmbeddedFlow, MovingPistonShockWithFirstAndSecondOrderBoundary) {
  const int Ns[3] = {40, 80, 160};
  for (double w : {0.4, 2.0})
    for (double deg : {0.0, 30.0}) {
      PistonErrors e[2][3];
      for (int order = 1; order <= 2; ++order)
        for (int r = 0; r < 3; ++r) e[order - 1][r] = piston_errors(Ns[r], order, w, w > 1 ? 0.1 : 0.15, deg);
      for (int order = 1; order <= 2; ++order) {
        const PistonErrors* x = e[order - 1];
        std::printf(
            "[ measured ] piston at %.1f, %2.0f deg, boundary order %d (N = 40, 80, 160): L1(p) %.3e %.3e %.3e "
            "(orders %.2f %.2f); shock offset %+.2f %+.2f %+.2f cells; near-wall |p - p*| / p* %.1e %.1e %.1e\n",
            w, deg, order, x[0].l1, x[1].l1, x[2].l1, observed_order(x[0].l1, x[1].l1),
            observed_order(x[1].l1, x[2].l1), x[0].shock_offset, x[1].shock_offset, x[2].shock_offset, x[0].near_wall,
            x[1].near_wall, x[2].near_wall);
        EXPECT_GT(observed_order(x[0].l1, x[2].l1, 4.0), 0.55) << w << " " << deg << " " << order;
        for (int r = 0; r < 3; ++r) {
          EXPECT_LT(std::abs(x[r].shock_offset), 1.0) << w << " " << deg << " " << order << " " << Ns[r];
          EXPECT_LT(x[r].near_wall, r == 2 ? 1e-3 : 5e-2) << w << " " << deg << " " << order << " " << Ns[r];
        }
      }
      // The weak piston on the diagonal wall (no start-up lag): the second-order face states drive the
      // post-shock state next to the wall more accurately at every resolution.
      if (w < 1 && deg > 0) {
        for (int r = 0; r < 3; ++r) EXPECT_LT(e[1][r].near_wall, e[0][r].near_wall) << Ns[r];
      }
    }
}

}  // namespace
}  // namespace cosim::fluid::test

namespace cosim::fluid::test {
namespace {

// Mach 3 flow past a cylinder: the bow shock's stand-off distance on the stagnation line against
// Billig's correlation for cylinders, delta / R = 0.386 exp(4.67 / M^2) = 0.648 at M = 3.
TEST(EmbeddedFlow, SupersonicCylinderBowShockStandOff) {
  const double R = 0.4;
  FluidScene s = load_fluid_scene(
      std::string(COSIM_SOURCE_DIR) + "/configs/supersonic_cylinder.yaml",
      {"fluid.mesh.cells=[160, 160]", "fluid.time.end=2.0", "fluid.embedded.bodies.0.radius=" + std::to_string(R),
       "fluid.embedded.bodies.0.center=[1.3, 1.0]"});
  auto sim = make_simulation(s);
  advance_to(*sim, s.t_end);
  PhaseFields f = sim->phase_fields(0);
  // Stagnation line y = 1: the shock is where the pressure first exceeds the mean of the free
  // stream and the post-normal-shock pressures (1 and 10.33 for M = 3), coming from upstream.
  const int N = 160, j = N / 2;
  const double p_mid = 0.5 * (1.0 + 10.333);
  double x_shock = 0;
  for (int i = 0; i < N; ++i) {
    const double p0 = f.p[static_cast<std::size_t>(j) * N + i], p1 = f.p[static_cast<std::size_t>(j) * N + i + 1];
    if (p0 < p_mid && p1 >= p_mid) {
      x_shock = (i + 0.5 + (p_mid - p0) / (p1 - p0)) * 2.0 / N;
      break;
    }
  }
  const double delta = (1.3 - R) - x_shock, billig = 0.386 * std::exp(4.67 / 9.0) * R;
  std::printf("Mach 3 cylinder: stand-off %.4f (Billig %.4f, %.1f%%)\n", delta, billig,
              100 * (delta - billig) / billig);
  EXPECT_NEAR(delta, billig, 0.06 * billig);
}

}  // namespace
}  // namespace cosim::fluid::test

namespace cosim::fluid::test {
namespace {

// Enstrophy sum(omega^2) dA over flow cells whose four neighbours are flow cells.
double enstrophy(const FluidSimulation& sim, int nx, int ny, double dx, double dy) {
  PhaseFields f = sim.phase_fields(0);
  auto kind = sim.embedded_categories();
  double z = 0;
  auto at = [&](int i, int j) { return static_cast<std::size_t>(j) * nx + i; };
  for (int j = 1; j + 1 < ny; ++j)
    for (int i = 1; i + 1 < nx; ++i) {
      if (kind[at(i, j)] > 1 || kind[at(i + 1, j)] > 1 || kind[at(i - 1, j)] > 1 || kind[at(i, j + 1)] > 1 ||
          kind[at(i, j - 1)] > 1)
        continue;
      const double w = (f.velocity[3 * at(i + 1, j) + 1] - f.velocity[3 * at(i - 1, j) + 1]) / (2 * dx) -
                       (f.velocity[3 * at(i, j + 1)] - f.velocity[3 * at(i, j - 1)]) / (2 * dy);
      z += w * w * dx * dy;
    }
  return z;
}

// Paper 9.1, small: Mach 0.05 flow over a step (a block standing on the floor). Without the
// correction the scheme's dissipation, which grows as 1/M, damps the shear layers leaving the
// step's corners; with it they roll up and the wake sheds vortices, so the enstrophy at t = 10
// (the flow has passed the block about once) is several times larger.
TEST(EmbeddedFlow, LowMachStepKeepsVorticityWithCorrection) {
  double z[2];
  for (int lm = 0; lm < 2; ++lm) {
    FluidScene s = load_fluid_scene(std::string(COSIM_SOURCE_DIR) + "/configs/low_mach_step.yaml",
                                    {"fluid.mesh.cells=[160, 80]", "fluid.time.end=10.0", "fluid.output.interval=0",
                                     std::string("fluid.numerics.low_mach=") + (lm ? "true" : "false")});
    auto sim = make_simulation(s);
    advance_to(*sim, s.t_end);
    z[lm] = enstrophy(*sim, 160, 80, 2.0 / 160, 1.0 / 80);
  }
  std::printf(
      "[ measured ] low-Mach step (160 x 80, t = 10): enstrophy %.4e without, %.4e with the correction (x%.2f)\n", z[0],
      z[1], z[1] / z[0]);
  EXPECT_GT(z[1], 1.6 * z[0]);
}

}  // namespace
}  // namespace cosim::fluid::test

namespace cosim::fluid::test {
namespace {

// Two phases at the embedded boundary (each phase mirrored about the wall): a uniform air/tungsten
// mixture flowing along a 30-degree wall stays uniform, and a mixture driven into the wall comes
// to rest there in both phases: the particles bounce off the structure (paper 9.6).
TEST(EmbeddedFlow, TwoPhaseMixtureAtAngledWall) {
  const double th = 30 * std::numbers::pi / 180.0;
  const std::string phases = R"(  phases:
    - {name: air, material: air}
    - {name: dust, material: tungsten}
  exchange: {velocity_relaxation: drag, drag_law: schiller_naumann, particle_diameter: 1.0e-5}
)";
  auto make = [&](double ux, double uy) {
    char state[512];
    std::snprintf(state, sizeof(state), "{p: 1.0e5, T: 300, alpha: [0.99, 0.01], velocity: [%.17g, %.17g]}", ux, uy);
    std::string sc =
        angled_wall_scene(30, 80, state, 3.0e-4, "  boundaries: {x_lower: transmissive, x_upper: transmissive}\n");
    sc.replace(sc.find("  phases: [{name: gas, eos: {type: ideal_gas, gamma: 1.4}}]\n"),
               std::string("  phases: [{name: gas, eos: {type: ideal_gas, gamma: 1.4}}]\n").size(), phases);
    return sc;
  };
  {  // parallel flow at 50 m/s
    auto sim = run_scene(make(50 * std::cos(th), 50 * std::sin(th)));
    auto kind = categories(*sim);
    double dmax = 0;
    for (int k = 0; k < 2; ++k) {
      PhaseFields f = sim->phase_fields(k);
      for (std::size_t c = 0; c < f.p.size(); ++c)
        if (kind[c] <= 1)
          dmax = std::max({dmax, std::abs(f.velocity[3 * c] - 50 * std::cos(th)) / 50,
                           std::abs(f.velocity[3 * c + 1] - 50 * std::sin(th)) / 50, std::abs(f.p[c] - 1e5) / 1e5});
    }
    std::printf("two-phase flow along a 30-degree wall: max relative deviation %.2e\n", dmax);
    EXPECT_LT(dmax, 1e-7);  // round-off of the tungsten EOS (pinf = 7.9e10 Pa against p = 1e5 Pa)
  }
  {  // driven into the wall at 50 m/s
    const double nx = -std::sin(th), ny = std::cos(th);
    auto sim = run_scene(make(-50 * nx, -50 * ny));
    auto kind = categories(*sim);
    PhaseFields air = sim->phase_fields(0), dust = sim->phase_fields(1);
    double un_air = 0, un_dust = 0, p = 0, alpha_dust = 0;
    int n = 0;
    const double tt = std::tan(th);
    for (int j = 0; j < 80; ++j)
      for (int i = 30; i < 50; ++i) {
        const std::size_t c = static_cast<std::size_t>(j) * 80 + i;
        if (kind[c] > 1) continue;
        const double x = (i + 0.5) / 80, y = (j + 0.5) / 80;
        const double dist = (y - kWallY0 - x * tt) * std::cos(th);
        if (dist > 0.015) continue;  // the first row of flow cells at the wall
        un_air += air.velocity[3 * c] * nx + air.velocity[3 * c + 1] * ny;
        un_dust += dust.velocity[3 * c] * nx + dust.velocity[3 * c + 1] * ny;
        p += air.p[c];
        alpha_dust += dust.alpha[c];
        ++n;
      }
    ASSERT_GT(n, 5);
    std::printf(
        "two-phase mixture into the wall: first row normal velocity air %.3f, dust %.3f m/s (incoming -50), "
        "p %.4g Pa, dust alpha %.4f (incoming 0.01)\n",
        un_air / n, un_dust / n, p / n, alpha_dust / n);
    // The wall stops both phases (heavy 10 um tungsten keeps arriving: drag time ~6 ms), the
    // particles pile up against it, the gas is compressed.
    EXPECT_LT(std::abs(un_air / n), 25.0);
    EXPECT_LT(std::abs(un_dust / n), 25.0);
    EXPECT_GT(alpha_dust / n, 0.013);
    EXPECT_GT(p / n, 1.3e5);
  }
}

}  // namespace
}  // namespace cosim::fluid::test

#include <fstream>
#include <nlohmann/json.hpp>

namespace cosim::fluid::test {
namespace {

// A run with a moving body reports what the flow cells gained or lost: a piston moving into a closed
// box must keep the gas mass (the boundary is not exactly conservative: we measure how close) and
// give the gas the work p* A w t of the exact piston pressure.
TEST(EmbeddedFlow, SummaryReportsTheBoundaryExchange) {
  const auto dir = cosim::test::scratch_path("emb_summary");
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "scene.yaml") << R"(
fluid:
  mesh: {cells: [40, 20], lower: [0.0, 0.0], upper: [2.0, 1.0]}
  phases: [{name: gas, eos: {type: ideal_gas, gamma: 1.4}}]
  time: {end: 0.5}
  boundaries: {x_lower: wall, x_upper: wall, y_lower: wall, y_upper: wall}
  embedded:
    bodies:
      - {shape: box, lower: [1.5, -0.5], upper: [2.6, 1.5], velocity: [-0.2, 0.0]}
  initial:
    state: {rho: 1.0, velocity: [0.0, 0.0], p: 1.0}
)";
  const std::string cmd = std::string(COSIM_BINARY_DIR) + "/bin/fluid_solver " + (dir / "scene.yaml").string() +
                          " --quiet --out " + (dir / "out").string() + " 2>/dev/null";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  std::ifstream in(dir / "out" / "summary.json");
  const auto j = nlohmann::json::parse(in);
  ASSERT_TRUE(j.contains("embedded"));
  const double dm = j["embedded"]["flow_totals_change"][0]["mass"].get<double>();
  const double de = j["embedded"]["flow_totals_change"][0]["energy"].get<double>();
  const double m0 = j["totals"]["start"][0]["mass"].get<double>();
  const double p_star = exact::solve_star({1, 0, 1}, {1.4, 0}, {1, -0.4, 1}, {1.4, 0}).p;
  const double work = p_star * 0.2 * 0.5 * 1.0;  // wall pressure x speed x time x height
  std::printf("flow cells: mass change %.3e of %.4f, energy change %.5f (piston work %.5f)\n", dm, m0, de, work);
  EXPECT_LT(std::abs(dm), 1e-3 * m0);
  EXPECT_NEAR(de, work, 0.05 * work);
  // The interface segments of every snapshot are written next to it: the piston face x = 1.4 at
  // t = 0.5 spans the domain height (plus the ghost layers): 1 + 4 dy of segments with normal -x.
  std::ifstream seg(dir / "out" / "fluid_interface_000001.csv");
  std::string line;
  std::getline(seg, line);
  EXPECT_EQ(line, "i,j,k,cx,cy,cz,nx,ny,nz,area,vx,vy,vz");
  double length = 0;
  while (std::getline(seg, line)) {
    double v[13];
    ASSERT_EQ(std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf", &v[0], &v[1], &v[2],
                          &v[3], &v[4], &v[5], &v[6], &v[7], &v[8], &v[9], &v[10], &v[11], &v[12]),
              13);
    if (v[6] < -0.99) {
      EXPECT_NEAR(v[3], 1.4, 1e-9);
      EXPECT_NEAR(v[10], -0.2, 1e-12);
      length += v[9];
    }
  }
  EXPECT_NEAR(length, 1.0 + 4 * 0.05, 1e-9);
  std::filesystem::remove_all(dir);
}

// The boundary's departure from conservation is a discretisation error: the same closed-box piston on
// 40 x 20, 80 x 40 and 160 x 80 cells, both boundary orders. The flow cells' mass change and the energy
// gain minus the exact piston work halve with each refinement (first order: covered cells are retired and
// uncovered ones filled, each a fraction of a cell per crossing).
TEST(EmbeddedFlow, BoundaryConservationErrorConvergesAtFirstOrder) {
  const double p_star = exact::solve_star({1, 0, 1}, {1.4, 0}, {1, -0.4, 1}, {1.4, 0}).p;
  const double work = p_star * 0.2 * 0.5 * 1.0;  // wall pressure x speed x time x height
  for (int order = 1; order <= 2; ++order) {
    double dm[3], de[3];
    for (int r = 0; r < 3; ++r) {
      const int n = 40 << r;
      char scene[1024];
      std::snprintf(scene, sizeof(scene), R"(
fluid:
  mesh: {cells: [%d, %d], lower: [0.0, 0.0], upper: [2.0, 1.0]}
  phases: [{name: gas, eos: {type: ideal_gas, gamma: 1.4}}]
  time: {end: 0.5}
  boundaries: {x_lower: wall, x_upper: wall, y_lower: wall, y_upper: wall}
  embedded:
    order: %d
    bodies:
      - {shape: box, lower: [1.5, -0.5], upper: [2.6, 1.5], velocity: [-0.2, 0.0]}
  initial:
    state: {rho: 1.0, velocity: [0.0, 0.0], p: 1.0}
)",
                    n, n / 2, order);
      auto sim = make_simulation(parse_fluid_scene(scene));
      const auto before = sim->totals();
      advance_to(*sim, 0.5);
      const auto after = sim->totals();
      dm[r] = (after[0].mass - before[0].mass) / before[0].mass;
      de[r] = (after[0].energy - before[0].energy) / work - 1.0;
    }
    std::printf(
        "[ measured ] closed-box piston, boundary order %d (40 x 20, 80 x 40, 160 x 80): flow-cell mass change "
        "%+.2e %+.2e %+.2e, energy gain / piston work - 1 %+.4f %+.4f %+.4f\n",
        order, dm[0], dm[1], dm[2], de[0], de[1], de[2]);
    for (int r = 0; r < 2; ++r) {
      EXPECT_GT(observed_order(std::abs(dm[r]), std::abs(dm[r + 1])), 0.8) << order << " " << r;
      EXPECT_GT(observed_order(std::abs(de[r]), std::abs(de[r + 1])), 0.8) << order << " " << r;
    }
    EXPECT_LT(std::abs(dm[2]), 2e-4);
    EXPECT_LT(std::abs(de[2]), 0.006);
  }
}

}  // namespace
}  // namespace cosim::fluid::test

namespace cosim::fluid::test {
namespace {

// 3D: a slab rotated 30 degrees about z moving along its normal into gas at rest (periodic in z):
// the gas between the slab and the shock has the exact piston state.
TEST(EmbeddedFlow, MovingPistonDiagonal3D) {
  const double th = 30 * std::numbers::pi / 180.0, w = 0.4;
  const double nx = std::cos(th), ny = std::sin(th);  // the slab's face normal into the gas (rotated +x face)
  char scene[2048];
  std::snprintf(scene, sizeof(scene), R"(
fluid:
  mesh: {cells: [48, 48, 4], lower: [0.0, 0.0, 0.0], upper: [1.0, 1.0, 0.0833333333333333]}
  phases: [{name: gas, eos: {type: ideal_gas, gamma: 1.4}}]
  time: {end: 0.15}
  boundaries: {z_lower: periodic, z_upper: periodic}
  embedded:
    bodies:
      - {shape: box, lower: [-0.62, -0.8, -0.5], upper: [0.58, 1.2, 0.6], velocity: [%.17g, %.17g, 0.0]}
  initial:
    state: {rho: 1.0, velocity: [0.0, 0.0, 0.0], p: 1.0}
)",
                w * nx, w * ny);
  FluidScene s = parse_fluid_scene(scene);
  s.embedded.bodies[0].rotation_deg = 30.0;  // rotation about z through the box centre (2D/3D boxes)
  auto sim = make_simulation(s);
  advance_to(*sim, s.t_end);
  exact::RiemannSolution ex({1, 0, 1}, {1.4, 0}, {1, -2 * w, 1}, {1.4, 0});
  const double p_star = ex.star().p;
  PhaseFields f = sim->phase_fields(0);
  auto kind = categories(*sim);
  // The slab's +x face, rotated about the box centre; probe cells 0.04..0.10 ahead of the moving
  // face near the domain centre, where the exact state is uniform.
  const double cx = -0.02, cy = 0.2;  // box centre: the moving face starts through (0.5, 0.5)
  const double face0 = 0.6;           // half-width in x: the face is at distance 0.6 from the centre
  double psum = 0;
  int n = 0;
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 48; ++j)
      for (int i = 0; i < 48; ++i) {
        const std::size_t c = (static_cast<std::size_t>(k) * 48 + j) * 48 + i;
        if (kind[c] > 1) continue;
        const double x = (i + 0.5) / 48, y = (j + 0.5) / 48;
        const double dist = (x - cx) * nx + (y - cy) * ny - face0 - w * s.t_end;  // ahead of the face now
        const double along = -(x - cx) * ny + (y - cy) * nx;
        if (dist < 0.04 || dist > 0.10 || std::abs(along) > 0.2) continue;
        psum += f.p[c];
        ++n;
      }
  ASSERT_GT(n, 8);
  std::printf("3D slab at 30 deg moving at %.1f: gas pressure %.4f (exact %.4f, %d cells)\n", w, psum / n, p_star, n);
  EXPECT_NEAR(psum / n, p_star, 0.005 * p_star);
}

}  // namespace
}  // namespace cosim::fluid::test

namespace cosim::fluid::test {
namespace {

// 3D piston convergence study: a slab moving at w = 0.4 along its normal into gas at rest, L1
// error of the pressure against the exact piston pressure between the moving face and the shock
// (4 cells at the shock excluded, as in 2D). deg = 0: a slab with its face normal to x on an
// N x 4 x 4 grid (periodic in y and z, a 1D problem run by the 3D solver); deg = 30: the slab
// rotated 30 degrees about z on an N x N x 4 grid (periodic in z), error within 0.3 along the
// face of the domain's middle (the waves from where the face meets y = 0 and y = 1 stay outside).
double piston_error_3d(int N, int order, double deg) {
  const double w = 0.4, t_end = 0.15, th = deg * std::numbers::pi / 180.0;
  const double nx = std::cos(th), ny = std::sin(th);  // the moving face's normal into the gas
  const int ny_cells = deg > 0 ? N : 4;
  const double ly = ny_cells / static_cast<double>(N), lz = 4.0 / N;
  // deg = 0: face at x = kWallY0 (off the cell faces). deg = 30: the box of MovingPistonDiagonal3D,
  // whose rotated +x face starts through (0.5, 0.5).
  const double cx = deg > 0 ? -0.02 : kWallY0 - 0.6, cy = deg > 0 ? 0.2 : 0.5 * ly, half = 0.6;
  char scene[2048];
  std::snprintf(scene, sizeof(scene), R"(
fluid:
  mesh: {cells: [%d, %d, 4], lower: [0.0, 0.0, 0.0], upper: [1.0, %.17g, %.17g]}
  phases: [{name: gas, eos: {type: ideal_gas, gamma: 1.4}}]
  time: {end: %g}
  boundaries: {%s z_lower: periodic, z_upper: periodic}
  embedded:
    bodies:
      - {shape: box, lower: [%.17g, %.17g, -0.5], upper: [%.17g, %.17g, 0.6], velocity: [%.17g, %.17g, 0.0]}
  initial:
    state: {rho: 1.0, velocity: [0.0, 0.0, 0.0], p: 1.0}
)",
                N, ny_cells, ly, lz, t_end, deg > 0 ? "" : "y_lower: periodic, y_upper: periodic,", cx - half, cy - 1.0,
                cx + half, cy + 1.0, w * nx, w * ny);
  FluidScene s = parse_fluid_scene(scene, {"fluid.embedded.order=" + std::to_string(order)});
  s.embedded.bodies[0].rotation_deg = deg;  // about z through the box centre
  auto sim = make_simulation(s);
  advance_to(*sim, s.t_end);
  exact::RiemannSolution ex({1, 0, 1}, {1.4, 0}, {1, -2 * w, 1}, {1.4, 0});
  const double shock = -ex.left_tail() * t_end, p_star = ex.star().p;
  PhaseFields f = sim->phase_fields(0);
  auto kind = categories(*sim);
  double err = 0;
  int n = 0;
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < ny_cells; ++j)
      for (int i = 0; i < N; ++i) {
        const std::size_t c = (static_cast<std::size_t>(k) * ny_cells + j) * N + i;
        if (kind[c] > 1) continue;
        const double x = (i + 0.5) / N, y = (j + 0.5) / N;
        const double dist = (x - cx) * nx + (y - cy) * ny - half;  // from the face's initial position
        const double along = -(x - cx) * ny + (y - cy) * nx;       // 0 on the normal through the box centre
        if ((deg > 0 && std::abs(along) > 0.3) || dist > shock - 4.0 / N) continue;
        err += std::abs(f.p[c] - p_star);
        ++n;
      }
  EXPECT_GT(n, 0);
  return err / n;
}

TEST(EmbeddedFlow, MovingPiston3DConvergence) {
  for (double deg : {0.0, 30.0}) {
    const int Ns[2][3] = {{40, 80, 160}, {32, 64, 128}};
    const int* N = Ns[deg > 0 ? 1 : 0];
    double e[2][3];
    for (int order = 1; order <= 2; ++order)
      for (int r = 0; r < 3; ++r) e[order - 1][r] = piston_error_3d(N[r], order, deg);
    for (int order = 1; order <= 2; ++order)
      std::printf(
          "3D piston at %2.0f deg (N = %d, %d, %d), boundary order %d: L1(p) %.3e %.3e %.3e, orders %.2f %.2f\n", deg,
          N[0], N[1], N[2], order, e[order - 1][0], e[order - 1][1], e[order - 1][2],
          observed_order(e[order - 1][0], e[order - 1][1]), observed_order(e[order - 1][1], e[order - 1][2]));
    // Both treatments converge. Order 2 < order 1 is not asserted: a shock's error is its smearing,
    // whatever the boundary (MovingPistonShockWithFirstAndSecondOrderBoundary), and on the diagonal
    // slab the two are within the noise of the face's staircase at 64 cells.
    for (int order = 1; order <= 2; ++order) {
      EXPECT_LT(e[order - 1][1], e[order - 1][0]) << deg << " order " << order;
      EXPECT_LT(e[order - 1][2], 0.5 * e[order - 1][0]) << deg << " order " << order;
    }
  }
}

}  // namespace
}  // namespace cosim::fluid::test
