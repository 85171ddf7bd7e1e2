// docs/protocol.md cannot go stale: its worked example of the Robin load is what solid_solver's code computes, and
// its minimal client, taken from the page and run as the solid of configs/piston_2d.yaml against fluid_solver and
// the coupler, follows solid_solver in every coupling mode.
#include <gtest/gtest.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <fstream>

#include "coupled_test_util.h"
#include "solid_solver/core/robin_step.h"
#include "solid_solver/core/simulation.h"

using namespace cosim;
using namespace cosim::test;

namespace {
std::string protocol_doc() { return read_text(fs::path(COSIM_SOURCE_DIR) / "docs" / "protocol.md"); }
}  // namespace

// A rigid block [-1, 0] x [0, 0.8] m at 10 m/s, its -x face under p = 2e5 Pa, Z = 529.15 Pa s/m and its +x face under
// p = 1e5 Pa, Z = 374.166 Pa s/m, one step of 1e-4 s: the heavy (80 kg) and the light (0.008 kg) rows of the table.
TEST(CoupledProtocol, RobinWorkedExampleIsWhatTheSolidDoes) {
  const std::string doc = protocol_doc();
  const double dt = 1e-4, v = 10.0;
  for (double mass : {80.0, 0.008}) {
    solid::Simulation sim(solid::parse_solid_scene(fmt::format(R"(
solid:
  mesh: {{cells: [1, 1], lower: [-1, 0], upper: [0, 0.8]}}
  blocks:
    - {{name: piston, rigid: true, density: {}, initial: {{velocity: [{}, 0]}}}}
  time: {{end: 1.0}}
)",
                                                               mass / 0.8, v)));
    ASSERT_NEAR(sim.rigid_bodies().at(0).mass, mass, 1e-12 * mass);
    const solid::BoundaryFaces& f = sim.boundary_faces();
    std::vector<double> p(f.count, 0.0), z(f.count, 0.0);
    double trace = 0;
    for (int i = 0; i < f.count; ++i) {
      const double nx = f.normal[2 * static_cast<std::size_t>(i)];
      if (std::abs(nx) < 0.5) continue;
      ASSERT_NEAR(f.velocity[2 * static_cast<std::size_t>(i)], v, 1e-12);
      p[i] = nx < 0 ? 2e5 : 1e5;
      z[i] = nx < 0 ? 529.15 : 374.166;
      trace += z[i] * f.area[i];
    }
    const double x0 = sim.rigid_bodies()[0].X[0];
    sim.set_face_pressures(p);
    sim.set_face_impedances(z);
    sim.advance(dt);
    const double v1 = sim.rigid_bodies()[0].V[0], dx = sim.rigid_bodies()[0].X[0] - x0;
    const double theta = solid::robin_theta(dt * trace / mass), vc = (1 - theta) * v + theta * v1;
    // The page's row, from its second column: "| dt tr K / M | theta | v' | dt v' | the two face pressures |".
    const std::string row =
        fmt::format("| {:.6g} | {:.10g} | {:.12g} | {:.10g} | {:.10g}, {:.10g} |", dt * trace / mass, theta, v1, dx,
                    2e5 + 529.15 * (v - vc), 1e5 + 374.166 * (vc - v));
    std::printf("[ measured ] M = %g kg: theta %.10g, v' %.12g m/s, dt v' %.10g m\n", mass, theta, v1, dx);
    EXPECT_NE(doc.find(row), std::string::npos) << "docs/protocol.md lacks the row " << row;
  }
}

// The block under ```python title="minimal_piston.py"``` of docs/protocol.md as the solid of piston_2d (40 x 8 cells,
// 30 ms: the piston's first stroke, 0.35 m) against solid_solver, in each coupling mode.
TEST(CoupledProtocol, MinimalClientOfTheDocumentMatchesSolidSolver) {
  const std::string doc = protocol_doc(), open = "```python title=\"minimal_piston.py\"\n";
  const auto begin = doc.find(open);
  ASSERT_NE(begin, std::string::npos) << "docs/protocol.md has no " << open;
  const auto end = doc.find("\n```", begin + open.size());
  ASSERT_NE(end, std::string::npos);
  const fs::path client = run_dir("minimal_piston.py");
  std::ofstream(client) << doc.substr(begin + open.size(), end - begin - open.size()) << "\n";
  const std::string common = " --set fluid.mesh.cells=[40,8] --set coupling.time.end=0.03";
  for (const char* mode : {"robin", "impedance", "characteristic", "standard"}) {
    const std::string args = common + " --set coupling.mode=" + mode;
    const fs::path stock = run_dir(std::string("contract_stock_") + mode);
    const fs::path mine = run_dir(std::string("contract_minimal_") + mode);
    ASSERT_EQ(cosim_run(scene_file("piston_2d"), stock, args), 0) << run_logs(stock);
    ASSERT_EQ(
        cosim_run(scene_file("piston_2d"), mine, args + " --solid-exe '/usr/bin/python3 " + client.string() + "'"), 0)
        << run_logs(mine);
    const History a = read_history(stock), b = read_history(mine);
    ASSERT_GT(b.size(), 500u) << mode;
    EXPECT_NEAR(b.t.back(), 0.03, 1e-12) << mode;
    const TrajectoryDifference d = trajectory_difference(a, b);
    std::printf("[ measured ] minimal client vs solid_solver, %s: max |dx| = %.3e m of %.3f m travel\n", mode, d.worst,
                d.travel);
    EXPECT_GT(d.travel, 0.3) << mode;
    EXPECT_LT(d.worst, 1e-4 * d.travel) << mode;
    // It writes no summary.json: the energy account holds the fluid's part, and the launcher says why in one line.
    const nlohmann::json account = nlohmann::json::parse(read_text(mine / "energy_account.json"));
    EXPECT_TRUE(account["solid"].is_null()) << mode;
    EXPECT_NE(read_text(fs::path(mine.string() + ".log")).find("energy_account.json has the fluid's part only"),
              std::string::npos)
        << mode;
  }
}
