// Two-phase DEM verification: interface conditions, reduction to single phase, the water/air
// shock tube against the exact two-material solution, conservation, drag relaxation rate.
#include <gtest/gtest.h>

#include <algorithm>

#include "common/exact/exact_riemann.h"
#include "fluid_solver/physics/drag_laws.h"
#include "fluid_test_utils.h"

namespace cosim::fluid::test {
namespace {

const char* kWaterAir = R"(
fluid:
  mesh: {cells: [200], lower: [0.0], upper: [1.0]}
  phases:
    - {name: water, eos: {type: stiffened_gas, gamma: 4.4, pinf: 6.0e8, cv: 4186}}
    - {name: air, eos: {type: ideal_gas, gamma: 1.4, cv: 717.6}}
  time: {end: 1.0e-4}
  boundaries: {x_lower: periodic, x_upper: periodic}
  initial:
    state:
      p: 1.0e5
      velocity: [100.0]
      alpha: [0.999999, 0.000001]
      phases: [{rho: 1000.0}, {rho: 1.0}]
    regions:
      - box: {lower: [0.3], upper: [0.6]}
        state:
          p: 1.0e5
          velocity: [100.0]
          alpha: [0.000001, 0.999999]
          phases: [{rho: 1000.0}, {rho: 1.0}]
)";

// A water/air interface advected at uniform p and u: p and u stay uniform (docs/methods.md §2.4 and §2.6).
TEST(TwoPhaseDEM, UniformPressureAndVelocityAcrossInterface) {
  for (const char* rec : {"first_order", "muscl"}) {
    auto sim = run_scene(kWaterAir, {std::string("fluid.numerics.reconstruction=") + rec});
    double dp = 0, du = 0;
    for (int k = 0; k < 2; ++k) {
      PhaseFields f = sim->phase_fields(k);
      for (std::size_t i = 0; i < f.p.size(); ++i) {
        dp = std::max(dp, std::abs(f.p[i] - 1e5) / 1e5);
        du = std::max(du, std::abs(f.velocity[3 * i] - 100.0) / 100.0);
      }
    }
    std::printf("%s: max |dp|/p = %.2e, max |du|/u = %.2e after %ld steps\n", rec, dp, du, sim->steps());
    EXPECT_LT(dp, 1e-9) << rec;
    EXPECT_LT(du, 1e-9) << rec;
    // The interface did move (0.3 -> 0.31): the cell at x = 0.3075 is now mostly water.
    PhaseFields w = sim->phase_fields(0);
    EXPECT_GT(w.alpha[static_cast<std::size_t>(0.3075 * 200)], 0.5) << rec;
  }
}

// Two identical phases with the same states at uniform volume fraction reproduce the single-phase result.
TEST(TwoPhaseDEM, IdenticalPhasesEqualSinglePhase) {
  const std::string single = riemann_scene(1, 0, 1, 0.125, 0, 0.1, 0.5, 0.2, 200);
  auto s1 = run_scene(single);
  const std::string two = R"(
fluid:
  mesh: {cells: [200], lower: [0.0], upper: [1.0]}
  phases:
    - {name: a, eos: {type: ideal_gas, gamma: 1.4}}
    - {name: b, eos: {type: ideal_gas, gamma: 1.4}}
  time: {end: 0.2}
  initial:
    state: {rho: 1.0, velocity: [0.0], p: 1.0, alpha: [0.3, 0.7]}
    regions:
      - half_space: {point: [0.5], normal: [1.0]}
        state: {rho: 0.125, velocity: [0.0], p: 0.1, alpha: [0.3, 0.7]}
)";
  auto s2 = run_scene(two);
  PhaseFields ref = s1->phase_fields(0);
  for (int k = 0; k < 2; ++k) {
    PhaseFields f = s2->phase_fields(k);
    double err = 0;
    for (std::size_t i = 0; i < f.rho.size(); ++i) {
      err = std::max(err, std::abs(f.rho[i] - ref.rho[i]));
      err = std::max(err, std::abs(f.p[i] - ref.p[i]));
      err = std::max(err, std::abs(f.velocity[3 * i] - ref.velocity[3 * i]));
      EXPECT_NEAR(f.alpha[i], k == 0 ? 0.3 : 0.7, 1e-12);
    }
    EXPECT_LT(err, 1e-11) << "phase " << k;
  }
}

// Water/air shock tube (docs/methods.md §2.4): interface velocity 482.6 m/s (exact two-material solution).
TEST(TwoPhaseDEM, WaterAirShockTubeInterfaceVelocity) {
  const std::string scene = R"(
fluid:
  mesh: {cells: [400], lower: [0.0], upper: [1.0]}
  phases:
    - {name: water, eos: {type: stiffened_gas, gamma: 4.4, pinf: 6.0e8, cv: 4186}}
    - {name: air, eos: {type: ideal_gas, gamma: 1.4, cv: 717.6}}
  time: {end: 240.0e-6}
  initial:
    state:
      velocity: [0.0]
      alpha: [0.999999, 0.000001]
      p: 1.0e9
      phases: [{rho: 1000.0}, {rho: 50.0}]
    regions:
      - half_space: {point: [0.7], normal: [1.0]}
        state:
          velocity: [0.0]
          alpha: [0.000001, 0.999999]
          p: 1.0e5
          phases: [{rho: 1000.0}, {rho: 50.0}]
)";
  exact::Star star = exact::solve_star({1000, 0, 1e9}, {4.4, 6e8}, {50, 0, 1e5}, {1.4, 0});
  for (const char* rec : {"first_order", "muscl"}) {
    auto sim = run_scene(scene, {std::string("fluid.numerics.reconstruction=") + rec});
    PhaseFields w = sim->phase_fields(0), a = sim->phase_fields(1);
    // Velocity in the mixed cells of the interface (0.1 < alpha < 0.9), and its position.
    double usum = 0, n = 0, xi = 0;
    for (std::size_t i = 0; i + 1 < w.alpha.size(); ++i) {
      if (w.alpha[i] > 0.1 && w.alpha[i] < 0.9) {
        usum += 0.5 * (w.velocity[3 * i] + a.velocity[3 * i]);
        n += 1;
      }
      if (w.alpha[i] >= 0.5 && w.alpha[i + 1] < 0.5) xi = (i + 1.0) / 400.0;
    }
    ASSERT_GT(n, 0);
    const double u = usum / n;
    std::printf("%s: interface velocity %.2f m/s (exact %.2f), position %.4f (exact %.4f)\n", rec, u, star.u, xi,
                0.7 + star.u * 240e-6);
    EXPECT_NEAR(u, star.u, 0.02 * star.u) << rec;
    EXPECT_NEAR(xi, 0.7 + star.u * 240e-6, 0.01) << rec;
  }
}

// Periodic box without drag: per-phase mass and mixture momentum/energy conserved to round-off.
TEST(TwoPhaseDEM, ConservationInPeriodicBox) {
  const std::string scene = R"(
fluid:
  mesh: {cells: [24, 20], lower: [0.0, 0.0], upper: [1.0, 1.0]}
  phases:
    - {name: gas, material: air}
    - {name: dust, material: tungsten}
  exchange: {velocity_relaxation: none, pressure_relaxation: true}
  time: {end: 2.0e-4}
  boundaries: {x_lower: periodic, x_upper: periodic, y_lower: periodic, y_upper: periodic}
  initial:
    state: {p: 1.0e5, T: 300, velocity: [0.0, 0.0], alpha: [0.99, 0.01]}
    regions:
      - sphere: {center: [0.4, 0.5], radius: 0.2}
        state: {p: 5.0e6, T: 900, velocity: [50.0, -20.0], alpha: [0.8, 0.2]}
)";
  FluidScene s = parse_fluid_scene(scene);
  auto sim = make_simulation(s);
  auto t0 = sim->totals();
  advance_to(*sim, s.t_end);
  auto t1 = sim->totals();
  EXPECT_GT(sim->steps(), 20);
  double e0 = t0[0].energy + t0[1].energy, e1 = t1[0].energy + t1[1].energy;
  for (int k = 0; k < 2; ++k) EXPECT_NEAR(t1[k].mass, t0[k].mass, 1e-13 * t0[k].mass) << k;
  const double mscale = std::abs(t0[0].mass + t0[1].mass) * 50.0;  // |momentum| scale
  for (int d = 0; d < 2; ++d)
    EXPECT_NEAR(t1[0].momentum[d] + t1[1].momentum[d], t0[0].momentum[d] + t0[1].momentum[d], 1e-13 * mscale);
  EXPECT_NEAR(e1, e0, 1e-13 * e0);
  // Momentum did move between the phases: the non-conservative terms are active.
  EXPECT_GT(std::abs(t1[1].momentum[0] - t0[1].momentum[0]), 1e-8 * mscale);  // 1e5 x the tolerance
}

// Drag alone (uniform state, particles sliding through gas at rest): the slip decays as the law says.
TEST(TwoPhaseDEM, DragRelaxesSlipAtTheLawsRate) {
  for (const char* law : {"schiller_naumann", "clift_gauvin", "akhatov_vainshtein"}) {
    const std::string scene = std::string(R"(
fluid:
  mesh: {cells: [4], lower: [0.0], upper: [0.01]}
  phases:
    - {name: gas, material: air}
    - {name: dust, material: tungsten}
  exchange: {velocity_relaxation: drag, drag_law: )") +
                              law + R"(, particle_diameter: 1.0e-4, gas_viscosity: 1.8e-5}
  time: {end: 1.5e-3}
  boundaries: {x_lower: periodic, x_upper: periodic}
  initial:
    state:
      p: 1.0e5
      T: 300
      alpha: [0.99, 0.01]
      phases: [{velocity: [0.0]}, {velocity: [10.0]}]
)";
    FluidScene s = parse_fluid_scene(scene);
    auto sim = make_simulation(s);
    PhaseFields g0 = sim->phase_fields(0), p0 = sim->phase_fields(1);
    const double mg = g0.alpha[0] * g0.rho[0], mp = p0.alpha[0] * p0.rho[0];
    const double rho_g = g0.rho[0], alpha_p = p0.alpha[0];
    // Reference: RK4 on d(du)/dt = -beta(|du|) (1/mg + 1/mp) du with small steps.
    double du = 10.0;
    const int nsteps = 30000;
    const double h = s.t_end / nsteps;
    auto rhs = [&](double x) {
      return -drag_beta(s.exchange.drag_law, alpha_p, rho_g, std::abs(x), 1e-4, 1.8e-5) * (1 / mg + 1 / mp) * x;
    };
    for (int i = 0; i < nsteps; ++i) {
      const double k1 = rhs(du), k2 = rhs(du + 0.5 * h * k1), k3 = rhs(du + 0.5 * h * k2), k4 = rhs(du + h * k3);
      du += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
    }
    advance_to(*sim, s.t_end);
    const double num = sim->phase_fields(0).velocity[0] - sim->phase_fields(1).velocity[0];
    std::printf("%s: slip after %.2f s: %.5f m/s (reference %.5f), %ld steps\n", law, s.t_end, -num, du, sim->steps());
    EXPECT_LT(du, 5.0) << law;  // the slip did relax substantially
    EXPECT_GT(du, 0.1) << law;
    EXPECT_NEAR(-num, du, 0.01 * du) << law;
  }
}

TEST(DragLaws, KnownValues) {
  // Schiller-Naumann at Re = 100: C_D = 0.24 (1 + 0.15 * 100^0.687) = 1.09173
  EXPECT_NEAR(drag_cd_re(DragLaw::SchillerNaumann, 100.0, 0.0) / 100.0, 1.09173, 1e-5);
  EXPECT_NEAR(drag_cd_re(DragLaw::SchillerNaumann, 2000.0, 0.0) / 2000.0, 0.44, 1e-12);
  // Stokes limit: C_D Re -> 24 for every law.
  for (DragLaw l : {DragLaw::SchillerNaumann, DragLaw::CliftGauvin, DragLaw::AkhatovVainshtein})
    EXPECT_NEAR(drag_cd_re(l, 0.0, 0.0), 24.0, 1e-12);
  // Clift-Gauvin adds the Newton-regime term: C_D(1e4) = 24/1e4 (1 + 0.15 1e4^0.687) + 0.42/(1 + 42500 1e4^-1.16)
  const double cg = 24e-4 * (1 + 0.15 * std::pow(1e4, 0.687)) + 0.42 / (1 + 42500 * std::pow(1e4, -1.16));
  EXPECT_NEAR(drag_cd_re(DragLaw::CliftGauvin, 1e4, 0.0) / 1e4, cg, 1e-12);
  // Akhatov-Vainshtein blends continuously between its dilute and dense branches.
  const double a1 = drag_cd_re(DragLaw::AkhatovVainshtein, 50, 0.08 - 1e-9);
  const double a2 = drag_cd_re(DragLaw::AkhatovVainshtein, 50, 0.08 + 1e-9);
  EXPECT_NEAR(a1, a2, 1e-6 * a1);
}

}  // namespace
}  // namespace cosim::fluid::test
