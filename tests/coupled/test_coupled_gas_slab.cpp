// The deformable piston of configs/piston_light_2d.yaml (a gas slab in solid_solver between two gas chambers)
// against an all-Eulerian reference: the same three gases (one gamma) on a fine 1D fluid_solver grid, where the
// slab's ends are contact discontinuities. The coupled slab's ends (its -x and +x faces in the coupler's
// interface snapshot) must sit where the contacts are, for each interface condition.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <vector>

#include "common/io/hdf5_file.h"
#include "coupled_test_util.h"

using namespace cosim;
using namespace cosim::test;

namespace {

struct Ends {
  double left = 0, right = 0;  // [m]
};

// The contacts of the 1D reference at t = 0.02 s: where the density crosses the geometric mean of the slab's
// and the chambers' densities (the slab is `ratio` times denser than the chambers at the start).
Ends euler_reference(double ratio) {
  const fs::path dir = run_dir("slab_reference_" + std::to_string(static_cast<int>(1000 * ratio)));
  fs::create_directories(dir);
  const fs::path scene = dir / "scene.yaml";
  std::ofstream(scene)
      << "name: slab_reference\nfluid:\n  mesh: {cells: [4000], lower: [-2.0], upper: [2.0]}\n"
         "  phases: [{name: gas, eos: {type: ideal_gas, gamma: 1.4}}]\n"
         "  time: {end: 0.02, cfl: 0.5}\n  boundaries: {x_lower: wall, x_upper: wall}\n"
         "  initial:\n    state: {rho: 1.0, velocity: [0.0], p: 1.0e5}\n    regions:\n"
         "      - box: {lower: [-2.0], upper: [-1.0]}\n        state: {rho: 1.0, velocity: [0.0], p: 2.0e5}\n"
         "      - box: {lower: [-1.0], upper: [0.0]}\n        state: {rho: "
      << ratio << ", velocity: [0.0], p: 1.5e5}\n  output: {interval: 0.02}\n";
  const std::string cmd = bin("fluid_solver").string() + " " + scene.string() + " --out " + (dir / "out").string() +
                          " --quiet > " + (dir / "log").string() + " 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << read_text(dir / "log");
  io::Hdf5File h(dir / "out" / "fluid_000001.h5", io::Hdf5File::Mode::ReadOnly);
  const auto rho = h.read_doubles("/cell/gas_density");
  const double thr = std::sqrt(ratio), dx = 4.0 / static_cast<double>(rho.size());
  Ends e{1e9, -1e9};
  for (std::size_t i = 0; i < rho.size(); ++i)
    if (ratio > 1 ? rho[i] > thr : rho[i] < thr) {
      e.left = std::min(e.left, -2.0 + i * dx);
      e.right = std::max(e.right, -2.0 + (i + 1) * dx);
    }
  return e;
}

// The slab's ends in the coupler's last interface snapshot (area-weighted centres of its -x and +x faces).
Ends coupled_ends(const fs::path& run) {
  fs::path last;
  for (int i = 0; fs::exists(run / "coupler" /
                             ("interface_" + std::string(i < 10 ? "00000" : "0000") + std::to_string(i) + ".h5"));
       ++i)
    last = run / "coupler" / ("interface_" + std::string(i < 10 ? "00000" : "0000") + std::to_string(i) + ".h5");
  io::Hdf5File h(last, io::Hdf5File::Mode::ReadOnly);
  const auto n = h.read_doubles("/cell/normal"), x = h.read_doubles("/grid/coordinates");
  const auto con = h.read_int64s("/grid/connectivity");
  double l = 0, r = 0;
  int nl = 0, nr = 0;
  for (std::size_t f = 0; f < n.size() / 3; ++f) {
    const double cx = 0.5 * (x[3 * con[2 * f]] + x[3 * con[2 * f + 1]]);
    if (n[3 * f] < -0.9) l += cx, ++nl;
    if (n[3 * f] > 0.9) r += cx, ++nr;
  }
  return {l / std::max(nl, 1), r / std::max(nr, 1)};
}

}  // namespace

TEST(CoupledGasSlab, EndsFollowTheEulerianContactsForEachInterfaceCondition) {
  for (double ratio : {0.001, 0.01, 0.1, 10.0, 100.0, 1000.0}) {
    const Ends ref = euler_reference(ratio);
    std::printf("[ measured ] slab/gas density ratio %g: Eulerian reference (4000 cells) ends at %.4f and %.4f m\n",
                ratio, ref.left, ref.right);
    for (const char* mode : {"robin", "standard", "characteristic", "impedance"}) {
      if (ratio < 1 && std::string(mode) == "standard") continue;                    // blows up (the stability map)
      if ((ratio < 0.005 || ratio > 500) && std::string(mode) != "robin") continue;  // the default at the extremes
      const fs::path dir = run_dir(std::string("slab_") + mode + "_" + std::to_string(static_cast<int>(1000 * ratio)));
      ASSERT_EQ(cosim_run(scene_file("piston_light_2d"), dir,
                          std::string("--set coupling.time.end=0.02 --set coupling.output.interval=0.02 ") +
                              "--set coupling.mode=" + mode + " --set solid.blocks.0.density=" + std::to_string(ratio)),
                0)
          << run_logs(dir);
      const Ends e = coupled_ends(dir);
      const double err = std::max(std::abs(e.left - ref.left), std::abs(e.right - ref.right));
      std::printf("[ measured ]   %-14s ends at %.4f and %.4f m: max error %.4f m (%.2f fluid cells)\n", mode, e.left,
                  e.right, err, err / 0.1);
      // Standard and characteristic conditions follow the contacts within a third of a fluid cell on the 40 x 8
      // background (characteristic: also for the light slabs, which standard conditions cannot run). The
      // impedance weights without their last terms (paper eqs. 21-22) only relax the two sides towards each
      // other once per cycle, so their result depends on the step: up to 1.3 cells off (docs/benchmarks.md).
      // The Robin condition (the default): within 0.15 cells at every ratio from 0.001 to 1000 (measured 0.04-0.12).
      // The reference is not converged at the light ratios: the slab's sound speed (4.6 km/s at ratio 0.01) sets
      // its step and the chamber gas runs at CFL 0.04-0.08, which smears its contacts; 16,000 cells move its ends
      // by up to 0.009 m (0.0065 at ratio 0.01) and 32,000 cells 0.0014 m more. The wall order of the embedded
      // boundary moves the coupled ends by up to 0.01 m either way depending on the ratio (ratio 0.01: first order
      // 0.0149 m, the paper's extrapolated wall velocity 0.0071, with a four-cell limiter of it 0.0168, the default
      // 0.0119; ratio 0.1: 0.0011 / 0.0132 / 0.0081 / 0.0124); their means over the six ratios agree within 15%
      // (docs/deformable_structures.md, "Wall order at the paper's 50 x 50").
      const bool imp = std::string(mode) == "impedance", robin = std::string(mode) == "robin";
      const double tol = imp ? 0.15 : robin ? 0.015 : 0.035;
      EXPECT_LT(err, tol) << mode << " ratio " << ratio;
    }
  }
}
