// Block totals (solid_solver/io/block_history.h) and the block_history.csv a run writes: masses, mass-averaged
// velocities and energies per block, and the plastic work, checked against what they must be.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "solid_solver/io/block_history.h"
#include "solid_solver/materials/strength.h"
#include "solid_test_util.h"
#include "tests/support/scratch_dir.h"

using namespace cosim::solid;

namespace {
const char* kTwoBlocks = R"(
solid:
  mesh:
    cells: [8, 4]
    lower: [0, 0]
    upper: [2, 1]
    regions:
      - {block: heavy, lower: [1, -1], upper: [3, 2]}
  blocks:
    - {name: light, eos: {type: linear_elastic, bulk_modulus: 1.0e9}, density: 1.0, initial: {velocity: [3.0, -1.0]}}
    - {name: heavy, rigid: true, density: 50.0, initial: {velocity: [3.0, -1.0]}}
  time: {end: 1.0e-3}
  output: {interval: 5.0e-4, history_every: 10}
)";
}  // namespace

// Two stress-free blocks moving together: each block's mass is its density times its area, its
// mass-averaged velocity the common one, and the block kinetic energies add up to the solver's.
TEST(BlockHistory, TotalsOfTwoBlocksInUniformMotion) {
  Simulation sim(parse_solid_scene(kTwoBlocks));
  solid_test::run_to(sim, 1e-3);
  const auto t = block_totals(sim);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_NEAR(t[0].mass, 1.0 * 1.0, 1e-12);
  EXPECT_NEAR(t[1].mass, 50.0 * 1.0, 1e-10);
  for (const BlockTotals& b : t) {
    EXPECT_NEAR(b.momentum[0] / b.mass, 3.0, 1e-9);
    EXPECT_NEAR(b.momentum[1] / b.mass, -1.0, 1e-9);
    EXPECT_NEAR(b.kinetic, 0.5 * b.mass * 10.0, 1e-8 * b.mass);
    EXPECT_EQ(b.plastic_work, 0.0);
  }
  EXPECT_NEAR(t[0].kinetic + t[1].kinetic, sim.energy().kinetic, 1e-9 * sim.energy().kinetic);
  EXPECT_NEAR(t[0].internal, 0.0, 1e-9);  // unstrained
}

// The file of a standalone run: a header, one row per block at t = 0, every 10 steps and at each output (never
// twice for one step), times increasing, the values of the state.
TEST(BlockHistory, StandaloneRunWritesRowsAtOutputsAndEveryNSteps) {
  const auto dir = cosim::test::scratch_path("block_history_run");
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "scene.yaml") << kTwoBlocks;
  const std::string cmd = std::string(COSIM_BINARY_DIR) + "/bin/solid_solver " + (dir / "scene.yaml").string() +
                          " --out " + (dir / "out").string() + " --quiet > " + (dir / "log").string() + " 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  std::ifstream in(dir / "out" / "block_history.csv");
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line.rfind("time,step,block,mass,velocity_x", 0), 0u) << line;
  long rows = 0, last_step = -1;
  double last_t = -1;
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::vector<std::string> c;
    for (std::string cell; std::getline(ss, cell, ',');) c.push_back(cell);
    ASSERT_EQ(c.size(), 12u) << line;
    const double t = std::stod(c[0]);
    const long step = std::stol(c[1]);
    EXPECT_EQ(c[2], rows % 2 == 0 ? "light" : "heavy");
    if (rows % 2 == 0) {
      EXPECT_GT(step, last_step);  // a new record, never the same step twice
      EXPECT_GE(t, last_t);
      EXPECT_TRUE(step == 0 || step % 10 == 0 || std::abs(t - 5e-4) < 1e-12 || std::abs(t - 1e-3) < 1e-12) << line;
      last_step = step, last_t = t;
    }
    EXPECT_NEAR(std::stod(c[4]), 3.0, 1e-9);
    EXPECT_NEAR(std::stod(c[5]), -1.0, 1e-9);
    ++rows;
  }
  EXPECT_NEAR(last_t, 1e-3, 1e-12);
  EXPECT_GT(rows, 2 * 3);
}

// Plastic work in uniaxial strain (one steel element compressed at 100 /s, laterally confined): it equals the
// deviatoric work integral(s_xx D_xx V dt) less the elastic shear energy still stored, s:s V / (4 G), both
// computed here from the stress history alone.
TEST(BlockHistory, PlasticWorkIsTheDissipatedDeviatoricWork) {
  const double G = 8.0e10, Y = 1.0e9, L = 1e-3, vx = -0.1;
  Simulation sim(solid_test::uniaxial_strain_scene(
      "eos: {type: linear_elastic, bulk_modulus: 1.6e11}\n      density: 7800", G, Y));
  const State& st = sim.state();
  const double dt = 0.5 * sim.stable_dt();
  double w_dev = 0;
  for (int k = 0; k < 4000; ++k) {
    const double s_old = st.s[0], len_old = L + vx * sim.time();
    sim.advance(dt);
    // D_xx = vx / length at mid-step; V = length x L^2; trapezoid in s_xx.
    const double len_mid = 0.5 * (len_old + (L + vx * sim.time()));
    w_dev += 0.5 * (s_old + st.s[0]) * (vx / len_mid) * (len_mid * L * L) * dt;
  }
  const double stored = (st.s[0] * st.s[0] + st.s[1] * st.s[1] + st.s[2] * st.s[2]) / (4 * G) * st.vol[0];
  const auto t = block_totals(sim);
  std::printf("[ measured ] uniaxial strain to eps_p = %.3e: plastic work %.5e J, deviatoric work - stored %.5e J\n",
              st.eps_p[0], t[0].plastic_work, w_dev - stored);
  ASSERT_GT(st.eps_p[0], 1e-3);
  EXPECT_NEAR(t[0].plastic_work / (w_dev - stored), 1.0, 0.01);
  EXPECT_NEAR(t[0].max_plastic_strain, st.eps_p[0], 1e-15);
  EXPECT_NEAR(t[0].max_von_mises / Y, 1.0, 1e-9);
}
