// The default (Robin) interface condition on the light gas slab of configs/piston_light_2d.yaml (docs/methods.md
// §4.4) at a CI size of the stability map (bench/coupled/run_stability_map.py): stable and smooth up to CFL 1
// at slab/gas density ratios 0.001 and 1, and consistent in the step (the slab's velocity at 20 ms the same
// for every CFL number within 5% of its range over the run). Negative controls show that the measures
// discriminate: the standard conditions blow up on the same light slab, the impedance weights (paper eqs.
// 21-22) miss the consistency bound, and on a light rigid piston they swing it at 8x the Robin run's speed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <vector>

#include "coupled_test_util.h"

using namespace cosim;
using namespace cosim::test;

namespace {

// rms of v minus its moving average over t_c, relative to the largest |moving average|, on
// [t_c, t_end - t_c/2] (the stability map's high-frequency index: a ringing faster than any wave the fluid
// resolves; 1 ms is about 4 fluid cells of sound travel).
double high_frequency_index(const History& h, double t_c = 1e-3) {
  const double t_end = h.t.back();
  double step = t_c / 50;
  for (std::size_t i = 1; i < h.size(); ++i)
    if (h.t[i] > h.t[i - 1]) step = std::min(step, 0.5 * (h.t[i] - h.t[i - 1]));
  std::vector<double> u;
  for (double s = 0; s < t_end; s += step) {
    std::size_t i = std::upper_bound(h.t.begin(), h.t.end(), s) - h.t.begin();
    i = std::clamp<std::size_t>(i, 1, h.size() - 1);
    const double w = (s - h.t[i - 1]) / std::max(h.t[i] - h.t[i - 1], 1e-300);
    u.push_back(h.vx[i - 1] + w * (h.vx[i] - h.vx[i - 1]));
  }
  const int win = std::max(1, static_cast<int>(std::lround(t_c / step))), half = win / 2;
  std::vector<double> c(u.size() + 1, 0.0);
  for (std::size_t i = 0; i < u.size(); ++i) c[i + 1] = c[i] + u[i];
  double sum2 = 0, scale = 0;
  long n = 0;
  for (long i = half; i + (win - half) < static_cast<long>(u.size()); ++i) {
    const double s = static_cast<double>(i) * step;
    if (s < t_c || s > t_end - 0.5 * t_c) continue;
    const double lp = (c[i - half + win] - c[i - half]) / win;
    sum2 += (u[i] - lp) * (u[i] - lp);
    scale = std::max(scale, std::abs(lp));
    ++n;
  }
  return n > 0 && scale > 0 ? std::sqrt(sum2 / n) / scale : 1e9;
}

struct SlabRun {
  int exit_code = -1;
  History h;
};

SlabRun slab(const std::string& mode, double ratio, double cfl) {
  const fs::path dir = run_dir("stability_" + mode + "_" + std::to_string(static_cast<int>(1000 * ratio)) + "_" +
                               std::to_string(static_cast<int>(100 * cfl)));
  SlabRun r;
  r.exit_code = cosim_run(
      scene_file("piston_light_2d"), dir,
      "--set coupling.time.end=0.02 --set coupling.output.interval=0.02 --set coupling.mode=" + mode +
          " --set fluid.time.cfl=" + std::to_string(cfl) + " --set solid.numerics.cfl=" + std::to_string(cfl) +
          " --set solid.blocks.0.density=" + std::to_string(ratio));
  if (r.exit_code == 0) r.h = read_history(dir);
  return r;
}

// Spread of the velocity at the end over the runs, relative to the largest range of v(t) among them.
double spread_over_range(const std::vector<SlabRun>& runs) {
  double lo = 1e300, hi = -1e300, range = 0;
  for (const auto& r : runs) {
    lo = std::min(lo, r.h.vx.back());
    hi = std::max(hi, r.h.vx.back());
    range = std::max(range,
                     *std::max_element(r.h.vx.begin(), r.h.vx.end()) - *std::min_element(r.h.vx.begin(), r.h.vx.end()));
  }
  return (hi - lo) / range;
}

}  // namespace

TEST(InterfaceStability, RobinLightSlabIsStableSmoothAndConsistentUpToCfl1) {
  for (double ratio : {0.001, 1.0}) {
    std::vector<SlabRun> runs;
    for (double cfl : {0.2, 0.5, 1.0}) {
      runs.push_back(slab("robin", ratio, cfl));
      const SlabRun& r = runs.back();
      ASSERT_EQ(r.exit_code, 0) << "ratio " << ratio << " CFL " << cfl;
      ASSERT_GT(r.h.size(), 50u);
      for (double v : r.h.vx) ASSERT_TRUE(std::isfinite(v));
      const double H = high_frequency_index(r.h);
      std::printf("[ measured ] robin, ratio %g, CFL %.1f: %zu cycles, v(20 ms) = %.3f m/s, H = %.4f\n", ratio, cfl,
                  r.h.size() - 1, r.h.vx.back(), H);
      EXPECT_LT(H, 0.05) << "ratio " << ratio << " CFL " << cfl;
    }
    const double spread = spread_over_range(runs);
    std::printf("[ measured ] robin, ratio %g: v(20 ms) spread over CFL 0.2 .. 1.0 = %.2f%% of its range\n", ratio,
                100 * spread);
    EXPECT_LT(spread, 0.05) << "ratio " << ratio;
  }
}

TEST(InterfaceStability, TheMeasuresDiscriminate) {
  // Standard conditions (the fluid takes the wall velocity, the solid the fluid pressure) on the lightest slab.
  EXPECT_NE(slab("standard", 0.001, 0.5).exit_code, 0);
  // The impedance weights at ratio 1: stable, but the response depends on the step.
  const std::vector<SlabRun> imp = {slab("impedance", 1.0, 0.1), slab("impedance", 1.0, 1.0)};
  ASSERT_EQ(imp[0].exit_code, 0);
  ASSERT_EQ(imp[1].exit_code, 0);
  const double spread = spread_over_range(imp);
  std::printf(
      "[ measured ] impedance, ratio 1: v(20 ms) = %.2f / %.2f m/s at CFL 0.1 / 1.0, spread %.1f%% of its "
      "range\n",
      imp[0].h.vx.back(), imp[1].h.vx.back(), 100 * spread);
  EXPECT_GT(spread, 0.05);
}

// A light rigid piston (configs/piston_2d.yaml at density 0.01: 1% of the gas's mass per area) under the Robin
// conditions, whose fluid impedance the body takes implicitly on its translation and rotation: it stays between
// the chambers (the two-chamber ODE's turning points are 0 and 0.718 m; the gas's own inertia dominates), does
// not turn in its channel, moves with the gas (the chambers' Riemann problem puts the contact at 109.5 m/s; the
// piston reaches at most 1.12x that over 50 ms) and the interface creates almost no energy (energy_account.json:
// 3.5e-4 of the total). Under the impedance conditions the same piston shows the added-mass instability: its
// velocity swings with growing amplitude from the first cycle (+378, -368, +959 m/s within 12 cycles, 0.19 ms;
// about 8x the Robin run's fastest over the same time). Whether the fluid survives the swings depends on its
// wall treatment: a negative pressure stops it in cycle 19 (in cycle 12 with the paper's extrapolated wall
// velocity at 911 m/s; with a four-cell limiter of it the run went on to 50 ms, the piston at up to 959 m/s, and
// the interface pumped a third of the total energy into the gas). So the measures are read from whatever history
// the run left, stopped or not: its fastest speed against the Robin run's until then, and its energy account
// where it ran to the end.
TEST(InterfaceStability, LightRigidPistonStaysBetweenTheChambers) {
  constexpr double kContact = 109.48;  // [m/s], exact Riemann solution of the chambers (2e5 | 1e5 Pa, 1 kg/m^3)
  const std::string args =
      "--set solid.blocks.0.density=0.01 --set coupling.time.end=0.05 --set coupling.output.interval=0.05";
  const auto created = [](const fs::path& dir) {
    return nlohmann::json::parse(read_text(dir / "energy_account.json"))["interface_created_relative"].get<double>();
  };
  const auto fastest = [](const History& h, double until) {
    double v = 0;
    for (std::size_t i = 0; i < h.size() && h.t[i] <= until; ++i) v = std::max(v, std::abs(h.vx[i]));
    return v;
  };
  const fs::path dir = run_dir("light_rigid_robin");
  ASSERT_EQ(cosim_run(scene_file("piston_2d"), dir, args), 0) << run_logs(dir);
  const History h = read_history(dir);
  ASSERT_GT(h.size(), 1000u);
  double lo = 1e9, hi = -1e9, vy = 0;
  for (std::size_t i = 0; i < h.size(); ++i) {
    lo = std::min(lo, h.cx[i] - h.cx[0]);
    hi = std::max(hi, h.cx[i] - h.cx[0]);
    vy = std::max(vy, std::abs(h.vy[i]));
  }
  const double robin_created = created(dir);
  std::printf(
      "[ measured ] light rigid piston (robin): displacement in [%.3f, %.3f] m, largest |v_y| %.2e m/s, largest "
      "|v_x| %.1f m/s, interface-created energy %.2e of the total\n",
      lo, hi, vy, fastest(h, 1e9), robin_created);
  EXPECT_GT(lo, -0.05);
  EXPECT_LT(hi, 0.8);
  EXPECT_LT(vy, 1e-6);
  EXPECT_LT(fastest(h, 1e9), 1.5 * kContact);
  EXPECT_LT(std::abs(robin_created), 0.01);

  const fs::path imp = run_dir("light_rigid_impedance");
  const int rc = cosim_run(scene_file("piston_2d"), imp, args + " --set coupling.mode=impedance");
  const History g = read_history(imp);
  ASSERT_GT(g.size(), 5u) << run_logs(imp);
  const double until = g.t.back(), ratio = fastest(g, until) / fastest(h, until);
  std::printf(
      "[ measured ] light rigid piston (impedance): exit code %d at t = %.3g s after %zu cycles, largest |v_x| "
      "%.1f m/s, %.1fx the Robin run's until then%s",
      rc, until, g.size() - 1, fastest(g, until), ratio, rc == 0 ? ", " : "\n");
  EXPECT_GT(ratio, 4.0);
  if (rc == 0) {
    const double imp_created = created(imp);
    std::printf("interface-created energy %.2e of the total\n", imp_created);
    EXPECT_GT(imp_created, 0.05);
  }
}
