// Gas piston on a conforming mesh (docs/methods.md §8.2): rigid heavy piston between two ideal-gas chambers, all
// Lagrangian, against the two-chamber adiabatic ODE (common/verification/piston_ode.h) over three periods.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "common/verification/piston_ode.h"
#include "solid_test_util.h"

using namespace cosim::solid;
using cosim::verification::PistonOde;

namespace {
struct PistonRun {
  double err_plain = 0, err_rayleigh = 0;  // max |x - x_ode| / peak-to-peak amplitude of the ODE
  double amplitude = 0, energy_drift = 0;
  long steps = 0;
};

PistonRun run_piston(const std::vector<std::string>& overrides, double rho_piston) {
  std::vector<std::string> ov = overrides;
  ov.push_back("solid.output.snapshots=false");
  SolidScene s = load_solid_scene(std::string(COSIM_SOURCE_DIR) + "/configs/solid_piston_1d.yaml", ov);
  Simulation sim(s);
  const double A = s.dim == 2 ? s.upper[1] - s.lower[1] : (s.upper[1] - s.lower[1]) * (s.upper[2] - s.lower[2]);
  PistonOde ode;
  ode.area = A;
  ode.mass = rho_piston * A * 1.0;
  ode.p_left = 2e5;
  ode.p_right = 1e5;
  ode.v_left = A * 1.0;
  ode.v_right = A * 2.0;
  ode.gamma = 1.4;
  PistonOde ray = ode;
  ray.extra_mass = (1.0 * A * 1.0 + 1.0 * A * 2.0) / 3.0;  // gas masses / 3
  const auto tr = cosim::verification::integrate_piston(ode, s.t_end, 1e-5);
  const auto tr_r = cosim::verification::integrate_piston(ray, s.t_end, 1e-5);
  PistonRun r;
  r.amplitude = tr.x_max() - tr.x_min();
  const RigidBody& rb = sim.rigid_bodies().at(0);
  const double x0 = rb.X[0];
  const double e0 = sim.energy().total();
  double worst = 0, worst_r = 0;
  while (sim.time() < s.t_end * (1 - 1e-14)) {
    solid_test::run_to(sim, std::min(s.t_end, sim.time() + 1e-3));
    const double x = rb.X[0] - x0;
    worst = std::max(worst, std::abs(x - tr.x_at(sim.time())));
    worst_r = std::max(worst_r, std::abs(x - tr_r.x_at(sim.time())));
  }
  r.err_plain = worst / r.amplitude;
  r.err_rayleigh = worst_r / (tr_r.x_max() - tr_r.x_min());
  const auto e = sim.energy();
  r.energy_drift = (e.total() - e0 - e.boundary_work) / e0;
  r.steps = sim.steps();
  std::printf(
      "[ measured ] piston %dD rho_p/rho_g = %g: %ld steps, ODE period %.5f s, amplitude %.4f m, "
      "max deviation %.3f%% (plain ODE), %.3f%% (ODE + gas mass/3), energy drift %.1e\n",
      s.dim, rho_piston, r.steps, tr.period(), r.amplitude, 100 * r.err_plain, 100 * r.err_rayleigh, r.energy_drift);
  return r;
}
}  // namespace

// Density ratio 100: the gas holds 3% of the piston mass, which lengthens the period by about 0.5% (Rayleigh:
// effective mass m + m_gas/3) and so shifts the phase by 1.5% of a period after three periods: about 4% of the
// amplitude against the plain ODE, 0.03% against the ODE with the gas-inertia correction.
TEST(SolidPiston, HeavyPiston1DFollowsTwoChamberOde) {
  const PistonRun r = run_piston({}, 100.0);
  EXPECT_LT(r.err_rayleigh, 0.01);
  EXPECT_LT(r.err_plain, 0.05);
  EXPECT_LT(std::abs(r.energy_drift), 1e-9);
}

// Density ratio 1000 (three periods = 1.17 s): the plain quasi-static ODE itself is within 1%.
TEST(SolidPiston, HeavierPiston1DWithinOnePercentOfPlainOde) {
  const PistonRun r = run_piston({"solid.blocks.1.density=1000.0", "solid.time.end=1.17"}, 1000.0);
  EXPECT_LT(r.err_plain, 0.01);
  EXPECT_LT(std::abs(r.energy_drift), 1e-9);
}

// 2D channel, four elements across (the flow stays 1D: checks that hourglass control and the rigid piston's
// locked rotation keep it so).
TEST(SolidPiston, HeavyPiston2DChannel) {
  const PistonRun r = run_piston({"solid.mesh.cells=[80,4]", "solid.mesh.upper=[2,0.2]"}, 100.0);
  EXPECT_LT(r.err_rayleigh, 0.01);
  EXPECT_LT(std::abs(r.energy_drift), 1e-9);
}

TEST(SolidPiston, HeavyPiston3DStrip) {
  const PistonRun r =
      run_piston({"solid.mesh.cells=[80,1,1]", "solid.mesh.lower=[-2,0,0]", "solid.mesh.upper=[2,0.05,0.05]",
                  "solid.mesh.regions=[{block: piston, lower: [-1,-1,-1], upper: [0,1,1]}, "
                  "{block: gas_right, lower: [0,-1,-1], upper: [2,1,1]}]",
                  "solid.boundaries=[{set: x_lower, type: symmetry}, {set: x_upper, type: symmetry}, "
                  "{set: y_lower, type: symmetry}, {set: y_upper, type: symmetry}, "
                  "{set: z_lower, type: symmetry}, {set: z_upper, type: symmetry}]"},
                 100.0);
  EXPECT_LT(r.err_rayleigh, 0.01);
  EXPECT_LT(std::abs(r.energy_drift), 1e-9);
}

// The executable runs the shipped scene (a short run) and reports the piston in summary.json; a Gmsh mesh
// next to a scene file is found relative to it, and a bad mesh gives exit code 2 with file:line.
TEST(SolidPiston, ExecutableRunsSceneAndRelativeGmshPath) {
  namespace fs = std::filesystem;
  const fs::path exe = fs::path(COSIM_BINARY_DIR) / "bin" / "solid_solver";
  if (!fs::exists(exe)) GTEST_SKIP() << "solid_solver not built";
  const fs::path dir = fs::temp_directory_path() / "solid_piston_exe";
  fs::remove_all(dir);
  fs::create_directories(dir);
  auto run = [&](const std::string& args) {
    const std::string cmd = exe.string() + " " + args + " > " + (dir / "log.txt").string() + " 2>&1";
    const int rc = std::system(cmd.c_str());
    return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  };
  EXPECT_EQ(run(std::string(COSIM_SOURCE_DIR) + "/configs/solid_piston_1d.yaml --quiet --out " + (dir / "o1").string() +
                " --set solid.time.end=0.01 --set solid.output.snapshots=false"),
            0);
  std::ifstream in(dir / "o1" / "summary.json");
  ASSERT_TRUE(in.good());
  const auto j = nlohmann::json::parse(in);
  EXPECT_EQ(j["status"], "completed");
  ASSERT_EQ(j["rigid_bodies"].size(), 1u);
  EXPECT_EQ(j["rigid_bodies"][0]["block"], "piston");
  EXPECT_GT(j["rigid_bodies"][0]["velocity"][0].get<double>(), 0.0);  // pushed to the right
  EXPECT_LT(std::abs(j["energy"]["relative_balance_error"].get<double>()), 1e-12);
  fs::copy_file(std::string(COSIM_SOURCE_DIR) + "/tests/solid/data/two_blocks_2d.msh", dir / "plate.msh");
  const std::string scene = R"(solid:
  mesh: {type: gmsh, file: plate.msh}
  blocks:
    - {name: gas, eos: {type: ideal_gas, gamma: 1.4}, density: 1.0, initial: {pressure: 1.0e5}}
    - {name: steel, material: steel}
  boundaries:
    - {set: left, type: fixed}
  time: {end: 1.0e-6}
)";
  std::ofstream(dir / "scene.yaml") << scene;
  EXPECT_EQ(run((dir / "scene.yaml").string() + " --quiet --out " + (dir / "o2").string()), 0);
  std::ofstream(dir / "plate.msh", std::ios::app) << "garbage\n";
  EXPECT_EQ(run((dir / "scene.yaml").string() + " --quiet --out " + (dir / "o3").string()), 2);
  std::ifstream log(dir / "log.txt");
  const std::string text((std::istreambuf_iterator<char>(log)), {});
  EXPECT_NE(text.find("scene.yaml:2: solid.mesh.file:"), std::string::npos) << text;
  EXPECT_NE(text.find("plate.msh:50: expected a section header"), std::string::npos) << text;
}
