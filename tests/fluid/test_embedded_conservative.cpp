// The conservative embedded boundary (embedded.conservative, docs/methods.md §5.8): with a body moving through a
// closed box, each phase's mass in the flow cells stays what it was to round-off, and their momentum and energy
// change by exactly what the domain walls and the body's walls put in (summary.json's accounts); the walls' work is
// that of the exact piston pressure.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "common/checkpoint/part_file.h"
#include "common/exact/exact_riemann.h"
#include "fluid_solver/core/fluid_state_entries.h"
#include "tests/support/scratch_dir.h"

namespace cosim::fluid::test {
namespace {

nlohmann::json run_summary(const std::string& name, const std::string& scene, const std::string& sets = "") {
  const auto dir = cosim::test::scratch_path(name);
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "scene.yaml") << scene;
  const std::string cmd = std::string(COSIM_BINARY_DIR) + "/bin/fluid_solver " + (dir / "scene.yaml").string() +
                          " --quiet --out " + (dir / "out").string() + " " + sets + " 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  std::ifstream in(dir / "out" / "summary.json");
  return nlohmann::json::parse(in);
}

double num(const nlohmann::json& j) { return j.get<double>(); }

// Per phase: the flow cells' mass change less the domain boundary's inflow (the walls of the box: none), and the
// momentum and energy changes less the boundary's and the body's walls' shares; relative to the start's mass,
// mass times the sound speed c and energy.
struct Closure {
  double mass = 0, momentum = 0, energy = 0;
};
Closure closure(const nlohmann::json& j, std::size_t k, double c) {
  const auto& t = j["totals"];
  const auto& ch = j["embedded"]["flow_totals_change"][k];
  const auto& in = t["boundary_inflow"][k];
  const auto& wall = j["embedded"]["wall_exchange"][k];
  const double m0 = num(t["start"][k]["mass"]), e0 = num(t["start"][k]["energy"]);
  Closure out;
  out.mass = std::abs(num(ch["mass"]) - num(in["mass"])) / m0;
  for (int d = 0; d < 3; ++d)
    out.momentum = std::max(
        out.momentum, std::abs(num(ch["momentum"][d]) - num(in["momentum"][d]) - num(wall["momentum"][d])) / (m0 * c));
  out.energy = std::abs(num(ch["energy"]) - num(in["energy"]) - num(wall["energy"])) / e0;
  return out;
}

const char* kPistonBox = R"(
fluid:
  mesh: {cells: [40, 20], lower: [0.0, 0.0], upper: [2.0, 1.0]}
  phases: [{name: gas, eos: {type: ideal_gas, gamma: 1.4}}]
  time: {end: 0.5}
  boundaries: {x_lower: wall, x_upper: wall, y_lower: wall, y_upper: wall}
  embedded:
    conservative: true
    bodies:
      - {shape: box, lower: [1.5, -0.5], upper: [2.6, 1.5], velocity: [%g, 0.0]}
  initial:
    state: {rho: 1.0, velocity: [0.0, 0.0], p: 1.0}
)";

// A piston pushed into the gas (it covers cells) and pulled out of it (it uncovers them), both boundary orders: the
// mass to 1e-10 (the non-conservative boundary: 1e-3), momentum and energy closed to 1e-10 by the walls' exchange,
// which is the exact piston's work p* w t.
TEST(EmbeddedConservative, MovingPistonKeepsTheMassAndClosesTheAccounts) {
  for (double w : {-0.2, 0.2})
    for (const char* order : {"1", "2"}) {
      char scene[1024];
      std::snprintf(scene, sizeof scene, kPistonBox, w);
      const auto j = run_summary("emb_cons_piston", scene, std::string("--set fluid.embedded.order=") + order);
      ASSERT_TRUE(j["embedded"]["conservative"].get<bool>());
      const Closure cl = closure(j, 0, std::sqrt(1.4));
      const double p_star = exact::solve_star({1, 0, 1}, {1.4, 0}, {1, 2 * w, 1}, {1.4, 0}).p;
      const double work = -p_star * w * 0.5 * 1.0;  // wall pressure x speed into the gas x time x height
      const double de = num(j["embedded"]["wall_exchange"][0]["energy"]);
      std::printf("w %+.1f order %s: mass %.2e momentum %.2e energy %.2e; walls' work %.5f, exact %.5f\n", w, order,
                  cl.mass, cl.momentum, cl.energy, de, work);
      EXPECT_LT(cl.mass, 1e-10) << w << " " << order;
      EXPECT_LT(cl.momentum, 1e-10) << w << " " << order;
      EXPECT_LT(cl.energy, 1e-10) << w << " " << order;
      EXPECT_NEAR(de, work, 0.05 * std::abs(work)) << w << " " << order;
      EXPECT_EQ(num(j["embedded"]["wall_exchange"][0]["mass"]), 0.0);
    }
}

// Two gases in a closed box and a cylinder crossing it diagonally (it covers and uncovers cells on every side):
// each phase's mass to 1e-10, the mixture's momentum and energy closed by the walls' exchange.
TEST(EmbeddedConservative, CylinderCrossingABoxKeepsEachPhase) {
  const auto j = run_summary("emb_cons_cylinder", R"(
fluid:
  mesh: {cells: [40, 40], lower: [0.0, 0.0], upper: [1.0, 1.0]}
  phases:
    - {name: air, eos: {type: ideal_gas, gamma: 1.4}}
    - {name: helium, eos: {type: ideal_gas, gamma: 1.67}}
  time: {end: 2.0e-3}
  boundaries: {x_lower: wall, x_upper: wall, y_lower: wall, y_upper: wall}
  embedded:
    conservative: true
    bodies:
      - {shape: circle, center: [0.3, 0.35], radius: 0.15, segments: 96, velocity: [120.0, 80.0]}
  initial:
    state: {velocity: [0.0, 0.0], alpha: [0.7, 0.3], p: 1.0e5, phases: [{rho: 1.2}, {rho: 0.17}]}
    regions:
      - half_space: {point: [0.6, 0.0], normal: [1.0, 0.0]}
        state: {velocity: [0.0, 0.0], alpha: [0.2, 0.8], p: 2.0e5, phases: [{rho: 2.0}, {rho: 0.3}]}
)");
  ASSERT_EQ(j["embedded"]["flow_totals_change"].size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    const Closure cl = closure(j, k, 400.0);
    std::printf("phase %zu: mass %.2e\n", k, cl.mass);
    EXPECT_LT(cl.mass, 1e-10) << k;
  }
  // The mixture: the phases' momentum and energy exchange (relaxation) cancels.
  double e0 = 0, de = 0, m0 = 0, dmx = 0;
  for (std::size_t k = 0; k < 2; ++k) {
    const auto& ch = j["embedded"]["flow_totals_change"][k];
    const auto& wall = j["embedded"]["wall_exchange"][k];
    const auto& in = j["totals"]["boundary_inflow"][k];
    e0 += num(j["totals"]["start"][k]["energy"]);
    m0 += num(j["totals"]["start"][k]["mass"]);
    de += num(ch["energy"]) - num(in["energy"]) - num(wall["energy"]);
    dmx += num(ch["momentum"][0]) - num(in["momentum"][0]) - num(wall["momentum"][0]);
  }
  std::printf("mixture: energy %.2e momentum %.2e\n", std::abs(de) / e0, std::abs(dmx) / (m0 * 400.0));
  EXPECT_LT(std::abs(de), 1e-10 * e0);
  EXPECT_LT(std::abs(dmx), 1e-10 * m0 * 400.0);
}

// A static body at an angle with the gas streaming at it, second-order walls: the non-conservative boundary lets
// mass through the wall faces (eq. 25 extrapolates a face velocity that is not the wall's), the conservative one
// none.
TEST(EmbeddedConservative, StaticSecondOrderWallKeepsTheMass) {
  const char* scene = R"(
fluid:
  mesh: {cells: [50, 50], lower: [0.0, 0.0], upper: [1.0, 1.0]}
  phases: [{name: gas, eos: {type: ideal_gas, gamma: 1.4}}]
  time: {end: 0.3}
  boundaries: {x_lower: wall, x_upper: wall, y_lower: wall, y_upper: wall}
  embedded:
    order: 2
    bodies:
      - {shape: box, lower: [0.55, 0.3], upper: [0.8, 0.7], rotation: 30.0}
  initial:
    state: {rho: 1.0, velocity: [0.5, 0.2], p: 1.0}
)";
  const auto plain = run_summary("emb_cons_static_plain", scene);
  const auto cons = run_summary("emb_cons_static", scene, "--set fluid.embedded.conservative=true");
  const Closure a = closure(plain, 0, std::sqrt(1.4)), b = closure(cons, 0, std::sqrt(1.4));
  std::printf("mass: non-conservative %.2e, conservative %.2e; energy closure %.2e\n", a.mass, b.mass, b.energy);
  EXPECT_GT(a.mass, 1e-6);
  EXPECT_LT(b.mass, 1e-10);
  EXPECT_LT(b.energy, 1e-10);
  EXPECT_LT(b.momentum, 1e-10);
}

// A run stopped at a checkpoint set and restarted from it ends as the uninterrupted run: the totals, the wall
// exchange account (fluid.embedded_wall_exchange in the set) and the mass account bit for bit, conservative or not
// (the first geometry after the restart covers and uncovers nothing: the set's cells are already that geometry's).
TEST(EmbeddedConservative, ARestartEndsAsTheUninterruptedRunWithItsAccounts) {
  char scene[1024];
  std::snprintf(scene, sizeof scene, kPistonBox, -0.2);
  for (const std::string conservative : {"true", "false"}) {
    const std::string sets =
        "--set 'fluid.checkpoint={interval: 0.25, keep: 2}' --set fluid.output.interval=0.25 "
        "--set fluid.embedded.conservative=" +
        conservative;
    const auto whole = run_summary("emb_cons_restart_whole", scene, sets);
    const auto first = cosim::test::scratch_path("emb_cons_restart");
    run_summary("emb_cons_restart", scene, sets + " --set fluid.time.end=0.25");
    std::filesystem::path newest;
    for (const auto& e : std::filesystem::directory_iterator(first / "out" / "checkpoints"))
      if (e.is_directory() && e.path() > newest) newest = e.path();
    ASSERT_FALSE(newest.empty()) << conservative;
    const std::string cmd = std::string(COSIM_BINARY_DIR) + "/bin/fluid_solver " + (first / "scene.yaml").string() +
                            " --quiet --out " + (first / "out").string() + " " + sets + " --restart " +
                            newest.string() + " 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    std::ifstream in(first / "out" / "summary.json");
    const nlohmann::json restarted = nlohmann::json::parse(in);
    EXPECT_EQ(num(restarted["final_time"]), num(whole["final_time"])) << conservative;
    EXPECT_EQ(restarted["totals"]["end"], whole["totals"]["end"]) << conservative;
    EXPECT_EQ(restarted["embedded"]["wall_exchange"], whole["embedded"]["wall_exchange"]) << conservative;
    EXPECT_EQ(restarted["embedded"]["mass"], whole["embedded"]["mass"]) << conservative;
    EXPECT_NE(num(whole["embedded"]["wall_exchange"][0]["energy"]), 0.0) << conservative;
  }
}

// The fluid part's entries (fluid_state_entries.h): the wall exchange account written after the others, and a part
// from before it existed (no fluid.embedded_wall_exchange) read with the other accounts only.
TEST(FluidStateEntries, TheWallExchangeIsWrittenAndAnOlderPartReadsWithoutIt) {
  const auto dir = cosim::test::scratch_path("fluid_state_entries");
  std::filesystem::create_directories(dir);
  // One phase in 2D: 8 inflow values (mass, momentum[2], energy, per phase and side pair), 2 embedded, 4 wall.
  const std::vector<double> inflow = {1, 2, 3, 4, 5, 6, 7, 8}, embedded = {0.5, -0.25}, wall = {0.0, 1.5, -2.5, 3.5};
  std::vector<double> acc = inflow;
  acc.insert(acc.end(), embedded.begin(), embedded.end());
  const std::size_t base = acc.size();
  acc.insert(acc.end(), wall.begin(), wall.end());
  for (const bool with_wall : {true, false}) {
    const auto path = dir / (with_wall ? "new.h5" : "old.h5");
    {
      checkpoint::PartWriter w(path, "fluid");
      const std::vector<double> accounts(acc.begin(), with_wall ? acc.end() : acc.begin() + base);
      write_fluid_state(w, {{1.0, 2.0, 3.0}, accounts, 0.75, 12, 3, {}, CellRange{}}, embedded.size(),
                        with_wall ? wall.size() : 0);
      w.commit();
    }
    const checkpoint::PartReader r(path, "fluid");
    EXPECT_EQ(r.has("fluid.embedded_wall_exchange"), with_wall);
    const FluidStateEntries e = read_fluid_state(r, 3, CellRange{}, 0, inflow.size(), embedded.size(), wall.size());
    EXPECT_EQ(e.accounts, std::vector<double>(acc.begin(), with_wall ? acc.end() : acc.begin() + base));
    EXPECT_EQ(e.time, 0.75);
    EXPECT_EQ(e.steps, 12);
    EXPECT_EQ(e.conserved, (std::vector<double>{1.0, 2.0, 3.0}));
    // A part whose wall exchange has another length (another dimension or phase count) is refused.
    if (with_wall) {
      EXPECT_THROW(read_fluid_state(r, 3, CellRange{}, 0, inflow.size(), embedded.size(), 2 * wall.size()),
                   std::runtime_error);
    }
  }
}

}  // namespace
}  // namespace cosim::fluid::test
