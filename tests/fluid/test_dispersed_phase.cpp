// A dispersed particle phase (exchange.dispersed, docs/methods.md §2.8): the carrier's pressure, no acoustic
// waves of its own, a collision stress that keeps a packed cloud below close packing. A dense tungsten slab
// (10% by volume) thrown at 400 m/s against a wall through air: with the full DEM the particle phase is a
// compressible tungsten continuum, the air between the particles is squeezed out and the run stops with a
// negative air density; as a dispersed phase the slab packs against the wall below close packing, stops and
// comes back, each phase's mass and the total energy conserved, at a step set by the air.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>

#include "fluid_solver/core/scene.h"
#include "fluid_test_utils.h"

namespace cosim::fluid::test {
namespace {

const char* kSlab = R"(
fluid:
  mesh: {cells: [400], lower: [0.0], upper: [1.0]}
  phases:
    - {name: air, material: air}
    - {name: tungsten, material: tungsten}
  exchange: {velocity_relaxation: none, dispersed: true}
  time: {end: 1.5e-3, cfl: 0.4}
  boundaries: {x_lower: wall, x_upper: wall}
  initial:
    state: {p: 1.0e5, T: 300, velocity: [0.0], alpha: [0.999999, 0.000001]}
    regions:
      - box: {lower: [0.6], upper: [0.8]}
        state: {p: 1.0e5, T: 300, velocity: [400.0], alpha: [0.9, 0.1]}
)";

double mean_velocity(const PhaseFields& f) {
  double m = 0, mu = 0;
  for (std::size_t i = 0; i < f.rho.size(); ++i) {
    m += f.alpha[i] * f.rho[i];
    mu += f.alpha[i] * f.rho[i] * f.velocity[3 * i];
  }
  return mu / m;
}

TEST(DispersedPhase, DenseSlabPacksAgainstAWallStopsAndComesBack) {
  FluidScene s = parse_fluid_scene(kSlab);
  auto sim = make_simulation(s);
  const std::vector<PhaseTotals> t0 = sim->totals();
  const double dt0 = sim->stable_dt();
  double max_alpha = 0, u_arrival = 0;
  long before = 0;
  while (sim->time() < s.t_end * (1 - 1e-12)) {
    sim->advance(std::min(sim->stable_dt(), s.t_end - sim->time()));
    const PhaseFields p = sim->phase_fields(1);
    max_alpha = std::max(max_alpha, *std::max_element(p.alpha.begin(), p.alpha.end()));
    if (sim->time() < 0.45e-3) {
      u_arrival = mean_velocity(p);
      before = sim->steps();
    }
  }
  const std::vector<PhaseTotals> t1 = sim->totals();
  const double u_end = mean_velocity(sim->phase_fields(1));
  const double e0 = t0[0].energy + t0[1].energy, e1 = t1[0].energy + t1[1].energy;
  FluidScene full = parse_fluid_scene(kSlab, {"fluid.exchange.dispersed=false"});
  const double dt_full = make_simulation(full)->stable_dt();
  std::printf(
      "mean particle velocity %.1f m/s before the wall, %.1f m/s at the end (restitution %.2f); "
      "peak alpha %.3f; mass change %.1e / %.1e; energy change %.1e; first step %.3g s, %.1fx the full "
      "DEM's; %ld steps\n",
      u_arrival, u_end, -u_end / u_arrival, max_alpha, (t1[0].mass - t0[0].mass) / t0[0].mass,
      (t1[1].mass - t0[1].mass) / t0[1].mass, (e1 - e0) / e0, dt0, dt0 / dt_full, sim->steps());
  EXPECT_GT(u_arrival, 399.0);  // it arrived at full speed ...
  EXPECT_LT(u_end, -10.0);      // ... and came back
  EXPECT_GT(before, 0);
  EXPECT_LT(max_alpha, s.exchange.particle_stress.packing + 0.03);  // packed, at most a little beyond close packing
  EXPECT_LT(std::abs(t1[0].mass - t0[0].mass) / t0[0].mass, 1e-12);
  EXPECT_LT(std::abs(t1[1].mass - t0[1].mass) / t0[1].mass, 1e-12);
  EXPECT_LT(std::abs(e1 - e0) / e0, 1e-12);
  EXPECT_GT(dt0 / dt_full, 4.0);  // the air's step, not the tungsten's 4 km/s

  // The full DEM: the tungsten continuum squeezes the air out at the wall and the state becomes inadmissible.
  auto dem = make_simulation(full);
  EXPECT_THROW(advance_to(*dem, full.t_end), std::exception);
}

// Without its particle stress the slab would pack beyond close packing: the law is what stops it.
TEST(DispersedPhase, WithoutTheCollisionStressTheSlabOverpacks) {
  FluidScene s = parse_fluid_scene(kSlab, {"fluid.exchange.particle_stress.p_s=1e-3"});
  auto sim = make_simulation(s);
  double max_alpha = 0;
  try {
    while (sim->time() < 0.7e-3) {
      sim->advance(sim->stable_dt());
      const PhaseFields p = sim->phase_fields(1);
      max_alpha = std::max(max_alpha, *std::max_element(p.alpha.begin(), p.alpha.end()));
    }
  } catch (const std::exception&) { max_alpha = 1.0; }  // or it breaks down
  std::printf("peak alpha without the stress: %.3f\n", max_alpha);
  EXPECT_GT(max_alpha, 0.7);
}

// A dilute cloud (0.01% tungsten) thrown at a wall: the particles bounce off it. The kinetic energy of their normal
// motion becomes granular energy at the wall, whose pressure sends them back (docs/methods.md §2.9); without the
// granular temperature the single-velocity cloud stops at the wall and stays there. A denser cloud (0.2%) meets
// itself at the wall often enough that its inelastic collisions (restitution 0.9) take most of that energy: it
// comes back far slower, and with elastic collisions it comes back fast.
TEST(DispersedPhase, DiluteCloudBouncesOffAWall) {
  struct Result {
    double u_arrival = 0, u_end = 0, energy = 0;
  };
  const auto run = [](double alpha, const std::vector<std::string>& extra) {
    std::vector<std::string> sets = {fmt::format("fluid.initial.regions.0.state.alpha=[{}, {}]", 1 - alpha, alpha)};
    sets.insert(sets.end(), extra.begin(), extra.end());
    FluidScene s = parse_fluid_scene(kSlab, sets);
    auto sim = make_simulation(s);
    const std::vector<PhaseTotals> t0 = sim->totals();
    Result r;
    while (sim->time() < s.t_end * (1 - 1e-12)) {
      sim->advance(std::min(sim->stable_dt(), s.t_end - sim->time()));
      if (sim->time() < 0.45e-3) r.u_arrival = mean_velocity(sim->phase_fields(1));
    }
    r.u_end = mean_velocity(sim->phase_fields(1));
    const std::vector<PhaseTotals> t1 = sim->totals();
    r.energy = (t1[0].energy + t1[1].energy) / (t0[0].energy + t0[1].energy) - 1.0;
    return r;
  };
  const Result dilute = run(1e-4, {}), cold = run(1e-4, {"fluid.exchange.granular_temperature=false"});
  const Result dense = run(2e-3, {}), elastic = run(2e-3, {"fluid.exchange.restitution=1"});
  std::printf(
      "mean particle velocity before the wall / at the end [m/s]: 0.01%% cloud %.1f / %.1f (%.1f without granular "
      "temperature); 0.2%% cloud %.1f (%.1f with elastic collisions); energy change %.1e\n",
      dilute.u_arrival, dilute.u_end, cold.u_end, dense.u_end, elastic.u_end, dilute.energy);
  EXPECT_GT(dilute.u_arrival, 360.0);                // (it gathers the resting trace of particles on its way)
  EXPECT_LT(dilute.u_end, -0.4 * dilute.u_arrival);  // it bounced
  EXPECT_GT(cold.u_end, -0.05 * dilute.u_arrival);   // it stuck
  EXPECT_GT(dense.u_end, 0.25 * dilute.u_end);       // collisions took most of the rebound
  EXPECT_LT(elastic.u_end, -0.4 * dilute.u_arrival);
  EXPECT_LT(std::abs(dilute.energy), 1e-12);
  EXPECT_LT(std::abs(dense.energy), 1e-12);
}

// Where the particles are only a trace (alpha_p < particle_stress.skip_below on both sides of a face, no random
// motion) the collision stress and its dissipation are skipped. Against the full computation (skip_below: 0) on a
// 2D blast that throws a cloud (10% in a hot disc) into air with a trace of particles: the skip is taken (the
// fields differ) and changes nothing measurable: the gas's density, velocity and pressure within 1e-9 of their
// largest values, the volume fraction within 1e-11, the particles' density, velocity and granular temperature
// within 1e-7 (measured: gas 2e-11, alpha 2e-12, particles 1e-9 to 1e-8), far below the scheme's error. (The particles' pressure is the
// gas's; read back from tungsten's stiff EOS, p = (gamma - 1) rho e - gamma p_inf, it shows e's round-off 1e5-fold.)
TEST(DispersedPhase, ATraceSkipsTheCollisionStressWithoutAMeasurableChange) {
  const char* kCloud = R"(
fluid:
  mesh: {cells: [64, 64], lower: [0.0, 0.0], upper: [1.0, 1.0]}
  phases:
    - {name: air, material: air}
    - {name: tungsten, material: tungsten}
  exchange: {velocity_relaxation: drag, drag_law: akhatov_vainshtein, heat_transfer: ranz_marshall, dispersed: true}
  time: {end: 3.0e-4, cfl: 0.4}
  boundaries: {x_lower: transmissive, x_upper: wall, y_lower: transmissive, y_upper: transmissive}
  initial:
    state: {p: 1.0e5, T: 300, velocity: [0.0, 0.0], alpha: [0.999999, 0.000001]}
    regions:
      - sphere: {center: [0.35, 0.5], radius: 0.12}
        state: {p: 1.0e8, T: 3000, velocity: [0.0, 0.0], alpha: [0.9, 0.1]}
)";
  const auto run = [&](double skip) {
    FluidScene s = parse_fluid_scene(kCloud, {fmt::format("fluid.exchange.particle_stress.skip_below={}", skip)});
    auto sim = make_simulation(s);
    while (sim->time() < s.t_end * (1 - 1e-12)) sim->advance(std::min(sim->stable_dt(), s.t_end - sim->time()));
    return std::vector<PhaseFields>{sim->phase_fields(0), sim->phase_fields(1)};
  };
  const std::vector<PhaseFields> skip = run(1e-5), full = run(0.0);
  const auto max_abs = [](const std::vector<double>& v) {
    double m = 0;
    for (const double x : v) m = std::max(m, std::abs(x));
    return m;
  };
  const auto max_diff = [](const std::vector<double>& a, const std::vector<double>& b) {
    double m = 0;
    for (std::size_t i = 0; i < a.size(); ++i) m = std::max(m, std::abs(a[i] - b[i]));
    return m;
  };
  double any = 0;
  for (int k = 0; k < 2; ++k) {
    const PhaseFields &a = skip[static_cast<std::size_t>(k)], &b = full[static_cast<std::size_t>(k)];
    const double drho = max_diff(a.rho, b.rho) / max_abs(b.rho),
                 du = max_diff(a.velocity, b.velocity) / max_abs(b.velocity);
    const double dp = max_diff(a.p, b.p) / max_abs(b.p), dalpha = max_diff(a.alpha, b.alpha);
    std::printf(
        "phase %d: largest differences, relative to the field's largest value: rho %.2e, u %.2e, p %.2e; "
        "alpha %.2e\n",
        k, drho, du, dp, dalpha);
    const double tol = k == 0 ? 1e-9 : 1e-7;
    EXPECT_LT(drho, tol) << k;
    EXPECT_LT(du, tol) << k;
    if (k == 0) {
      EXPECT_LT(dp, tol);
    }
    EXPECT_LT(dalpha, 1e-11) << k;
    any = std::max({any, drho, du, dalpha});
  }
  const double dtheta = max_diff(skip[1].theta, full[1].theta) / max_abs(full[1].theta);
  std::printf("granular temperature: %.2e of its largest value (%.3g m^2/s^2)\n", dtheta, max_abs(full[1].theta));
  EXPECT_LT(dtheta, 1e-7);
  EXPECT_GT(max_abs(full[1].theta), 0.0);  // the cloud did meet the wall's particles
  EXPECT_GT(any, 0.0);                     // the skip was taken
}

TEST(DispersedPhase, SceneKeysAreChecked) {
  const auto error = [](const std::vector<std::string>& sets) -> std::string {
    try {
      parse_fluid_scene(kSlab, sets);
    } catch (const config::ConfigError& e) { return e.what(); }
    return "";
  };
  EXPECT_NE(error({"fluid.exchange.pressure_relaxation=false"}).find("pressure_relaxation"), std::string::npos);
  EXPECT_NE(error({"fluid.exchange.dispersed=false", "fluid.exchange.particle_stress.p_s=1"}).find("dispersed"),
            std::string::npos);
  EXPECT_NE(error({"fluid.exchange.particle_stress.packing=0.9"}).find("packing"), std::string::npos);
  EXPECT_NE(error({"fluid.exchange.particle_stress.skip_below=0.1"}).find("skip_below"), std::string::npos);
  EXPECT_NE(error({"fluid.exchange.granular_temperature=false", "fluid.exchange.restitution=0.5"}).find("restitution"),
            std::string::npos);
  EXPECT_NE(error({"fluid.exchange.restitution=1.5"}).find("restitution"), std::string::npos);
  EXPECT_NE(error({"fluid.numerics.flux=hllc"}).find("aufs"), std::string::npos);
  EXPECT_NE(error({"fluid.exchange.dispersed=false", "fluid.exchange.granular_temperature=true"}).find("dispersed"),
            std::string::npos);
}

}  // namespace
}  // namespace cosim::fluid::test
