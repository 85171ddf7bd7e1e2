// Paper 9.6 (configs/tungsten_blast_3d.yaml) at a CI size: a tungsten-laden blast on a steel target in 3D, two
// phases, embedded and coupled, 32^3 background and a 4 x 10 x 10 target, 0.3 ms. The run completes; each phase's
// mass in the flow cells changes only by what crossed the domain boundary and the target's moving walls, to
// round-off (fluid summary.json); on a free target
// the impulse of the force the coupler reports equals the target's momentum; with a softer target (yield stress
// lowered so that it yields at this resolution) the plastic work is positive and below the work done on it. Each
// phase's share of the force on the target (coupler/interface_phases.csv) adds up to the force.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "coupled_test_util.h"

using namespace cosim;
using namespace cosim::test;

namespace {

const std::string kCiSize =
    "--set fluid.mesh.cells=[32,32,32] --set solid.mesh.cells=[4,10,10] --set coupling.time.end=3e-4";

nlohmann::json read_json(const fs::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}

// Rows of a CSV file as maps column -> value.
std::vector<std::map<std::string, double>> read_csv(const fs::path& p) {
  std::ifstream in(p);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> cols;
  std::stringstream hs(line);
  for (std::string c; std::getline(hs, c, ',');) cols.push_back(c);
  std::vector<std::map<std::string, double>> rows;
  while (std::getline(in, line)) {
    std::stringstream ls(line);
    std::map<std::string, double> r;
    std::size_t i = 0;
    for (std::string c; std::getline(ls, c, ',') && i < cols.size(); ++i) {
      try {
        r[cols[i]] = std::stod(c);
      } catch (...) { r[cols[i]] = std::nan(""); }  // the block name
    }
    rows.push_back(r);
  }
  return rows;
}

TEST(TungstenBlast, CompletesAndConservesEachPhaseApartFromTheBoundaryFluxes) {
  const fs::path dir = run_dir("tungsten_blast");
  ASSERT_EQ(cosim_run(scene_file("tungsten_blast_3d"), dir, kCiSize), 0) << run_logs(dir);
  const nlohmann::json f = read_json(dir / "fluid" / "summary.json");
  EXPECT_EQ(f["status"], "completed");
  EXPECT_EQ(read_json(dir / "run_summary.json")["status"], "completed");  // the launcher's account of the run
  for (const char* sub : {"fluid/summary.json", "solid/summary.json", "coupler/coupler_summary.json"}) {
    const nlohmann::json j = read_json(dir / sub);  // every summary names the build
    EXPECT_TRUE(j.contains("version") && j.contains("git_commit")) << sub;
  }
  // Each phase's mass in the flow cells changes by what crossed the domain boundary and what the moving target's
  // walls pushed through the grid faces or the cells it covered and uncovered took along; nothing else, to
  // round-off (sums over 32^3 cells and hundreds of steps: 1e-11 of the mass).
  const auto& t = f["totals"];
  const auto& acc_mass = f["embedded"]["mass"];
  for (int k = 0; k < 2; ++k) {
    const double m0 = t["start"][k]["mass"], m1 = t["end"][k]["mass"];
    const double in = t["boundary_inflow"][k]["mass"], made = t["created"][k]["mass"];
    const double walls = acc_mass[k]["through_walls"], cells = acc_mass[k]["cells_uncovered"];
    const double lost = acc_mass[k]["unaccounted"];
    std::printf(
        "%-8s mass %.6g -> %.6g kg: through the domain boundary %+.6g kg, through the target's walls %+.3e kg, with "
        "the cells it covered or uncovered %+.3e kg, unaccounted %+.1e kg (%.1e)\n",
        t["start"][k]["phase"].get<std::string>().c_str(), m0, m1, in, walls, cells, lost, lost / m0);
    EXPECT_LT(in, 0.0);  // the blast leaves through the transmissive boundaries
    EXPECT_NEAR(made, walls + cells + lost, 1e-15 * m0) << k;
    EXPECT_LT(std::abs(lost), 1e-11 * m0) << k;
    EXPECT_LT(std::abs(made), 1e-3 * m0) << k;  // the target moves by a fraction of a cell
  }
  // The particles reach the target: the tungsten pressure there rises with the blast (the target is loaded by
  // both phases through the volume-fraction-weighted face pressure)
  const auto hist = read_csv(dir / "coupler" / "interface_history.csv");
  ASSERT_GT(hist.size(), 100u);
  double peak = 0;
  for (const auto& r : hist) peak = std::max(peak, r.at("pressure"));
  std::printf("peak mean face pressure %.3g Pa\n", peak);
  EXPECT_GT(peak, 50 * 1e5);
  // Each phase's share of the force (coupler/interface_phases.csv) adds up to the force of every cycle, and both
  // phases deliver a part of the impulse: the air's blast first, the particles' once the cloud arrives.
  const auto phases = read_csv(dir / "coupler" / "interface_phases.csv");
  ASSERT_EQ(phases.size(), hist.size());
  double impulse_air = 0, impulse_tungsten = 0, worst = 0, scale = 0;
  for (std::size_t i = 0; i < hist.size(); ++i) {
    ASSERT_EQ(phases[i].at("cycle"), hist[i].at("cycle"));
    for (const char* c : {"x", "y", "z"}) {
      const std::string col = std::string("force_") + c;
      const double sum = phases[i].at("air_" + col) + phases[i].at("tungsten_" + col);
      worst = std::max(worst, std::abs(sum - hist[i].at(col)));
      scale = std::max(scale, std::abs(hist[i].at(col)));
    }
    if (i + 1 < hist.size()) {
      const double dt = hist[i + 1].at("time") - hist[i].at("time");
      impulse_air += phases[i].at("air_force_x") * dt;
      impulse_tungsten += phases[i].at("tungsten_force_x") * dt;
    }
  }
  std::printf("impulse on the target: air %.6g N s, tungsten %.6g N s; phases vs force: %.1e N of %.3g N\n",
              impulse_air, impulse_tungsten, worst, scale);
  EXPECT_LT(worst, 1e-9 * scale);  // both rounded to 12 digits
  EXPECT_GT(impulse_air, 0.0);
  EXPECT_GT(impulse_tungsten, 0.0);
  const nlohmann::json acc = read_json(dir / "energy_account.json");
  std::printf("energy created at the interface: %.2e of the total\n", acc["interface_created_relative"].get<double>());
  EXPECT_LT(std::abs(acc["interface_created_relative"].get<double>()), 1e-2);
}

TEST(TungstenBlast, FreeTargetMomentumEqualsTheImpulseOfTheInterfaceForce) {
  const fs::path dir = run_dir("tungsten_blast_free");
  ASSERT_EQ(cosim_run(scene_file("tungsten_blast_3d"), dir, kCiSize + " --set solid.boundaries=[]"), 0)
      << run_logs(dir);
  const auto hist = read_csv(dir / "coupler" / "interface_history.csv");
  const auto blocks = read_csv(dir / "solid" / "block_history.csv");
  ASSERT_GT(hist.size(), 10u);
  // The force of cycle n acts on the solid over its step to cycle n + 1.
  double impulse = 0;
  for (std::size_t i = 0; i + 1 < hist.size(); ++i)
    impulse += hist[i].at("force_x") * (hist[i + 1].at("time") - hist[i].at("time"));
  const double p = blocks.back().at("mass") * blocks.back().at("velocity_x");
  std::printf("free target: impulse %.6g N s, momentum %.6g kg m/s (ratio %.12f)\n", impulse, p, p / impulse);
  EXPECT_GT(impulse, 0.0);
  EXPECT_NEAR(p, impulse, 0.01 * impulse);
}

TEST(TungstenBlast, PlasticWorkIsPositiveAndBelowTheWorkDoneOnTheTarget) {
  const fs::path dir = run_dir("tungsten_blast_soft");
  // 4340 steel's yield stress 792 MPa is not reached at this resolution (peak von Mises about 280 MPa): 100 MPa
  ASSERT_EQ(
      cosim_run(scene_file("tungsten_blast_3d"), dir, kCiSize + " --set solid.blocks.0.strength.yield_stress=1e8"), 0)
      << run_logs(dir);
  const auto blocks = read_csv(dir / "solid" / "block_history.csv");
  const nlohmann::json acc = read_json(dir / "energy_account.json");
  const double wp = blocks.back().at("plastic_work"), work = acc["solid"]["boundary_work"];
  std::printf("soft target: plastic work %.4g J of %.4g J done on it, max eps_p %.3g\n", wp, work,
              blocks.back().at("max_plastic_strain"));
  EXPECT_GT(wp, 0.0);
  EXPECT_LT(wp, work);
  EXPECT_GT(blocks.back().at("max_plastic_strain"), 0.0);
}

}  // namespace
