// The whole scene is checked before a run starts anything: each of the run's programs reads it with --check, the
// coupling section first, so that a mistake there is named as such (a typo in coupling.time was reported as
// fluid.time.end missing by whichever solver failed first) and no run directory is made. `cosim check` runs the
// same checks and writes nothing.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <fstream>
#include <utility>

#include "coupling_test_util.h"
#include "launcher/scene_check.h"

using namespace cosim::test;

namespace {

// configs/piston_2d.yaml with `from` replaced by `to`.
fs::path edited_scene(const fs::path& dir, const std::string& from, const std::string& to) {
  std::string s = read_file(fs::path(COSIM_SOURCE_DIR) / "configs" / "piston_2d.yaml");
  const std::size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) s.replace(at, from.size(), to);
  const fs::path p = dir / "scene.yaml";
  std::ofstream(p) << s;
  return p;
}

}  // namespace

TEST(SceneCheck, ATypoInTheCouplingSectionIsNamedBeforeAnythingStarts) {
  const fs::path dir = test_dir("check_typo");
  const fs::path scene = edited_scene(dir, "  time: {end: 0.37}", "  timd: {end: 0.37}");
  const fs::path run = dir / "run";
  auto [rc, log] = run_shell(dir, bin("cosim").string() + " run " + scene.string() + " --out " + run.string());
  EXPECT_EQ(rc, 2) << log;
  EXPECT_NE(log.find("coupler refuses the scene (nothing was started)"), std::string::npos) << log;
  EXPECT_NE(log.find("coupling.time: expected a section, but the key is missing (did you mean 'timd', given at line"),
            std::string::npos)
      << log;
  EXPECT_EQ(log.find("fluid.time"), std::string::npos) << log;  // not the solvers' consequence of it
  EXPECT_FALSE(fs::exists(run));
}

TEST(SceneCheck, CosimCheckAcceptsAGoodSceneAndNamesTheFirstBadSectionWritingNothing) {
  const fs::path dir = test_dir("check_cmd");
  const std::string cosim = bin("cosim").string(),
                    piston = (fs::path(COSIM_SOURCE_DIR) / "configs" / "piston_2d.yaml").string();
  auto [ok, out] = run_shell(dir, cosim + " check " + piston);
  EXPECT_EQ(ok, 0) << out;
  EXPECT_NE(out.find("valid; a coupled run"), std::string::npos) << out;
  // the plan: what each program will do
  EXPECT_NE(out.find("coupler: robin interface conditions"), std::string::npos) << out;
  EXPECT_NE(out.find("fluid: 2D, 160 x 8 cells (1280), 1 phase(s) (gas), aufs flux, state about"), std::string::npos)
      << out;
  EXPECT_NE(out.find("solid: 2D, 8 elements, 15 nodes, 1 block(s)"), std::string::npos) << out;
  EXPECT_NE(out.find("rigid bodies only"), std::string::npos) << out;
  auto [bad, err] = run_shell(dir, cosim + " check " + piston + " --set solid.blocks.0.density=-1");
  EXPECT_EQ(bad, 2) << err;
  EXPECT_NE(err.find("solid_solver refuses the scene"), std::string::npos) << err;
  EXPECT_NE(err.find("solid.blocks.0.density"), std::string::npos) << err;
  // Each program answers --check alone too, with nothing written.
  for (const char* exe : {"coupler", "fluid_solver", "solid_solver"}) {
    auto [rc, text] = run_shell(dir, bin(exe).string() + " " + piston + " --check");
    EXPECT_EQ(rc, 0) << exe << ": " << text;
  }
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1);  // out.log only
}

// The plan states the first step of the initial state and the size of the outputs. Sod (Toro test 1): the left
// state's c = sqrt(1.4) m/s limits, dt = cfl dx / c = 0.4 * 0.0025 / 1.1832 = 8.45e-4 s, 237 steps to 0.2 s;
// a snapshot holds density, 3 velocity components, pressure, temperature: 6 x 8 B x 400 cells = 19 KiB, and the
// run writes 5 (t = 0 and every 0.05 s).
TEST(SceneCheck, ThePlanStatesTheFirstStepAndTheOutputVolume) {
  const fs::path dir = test_dir("check_plan_fluid");
  auto [rc, log] = run_shell(
      dir, bin("cosim").string() + " check " + (fs::path(COSIM_SOURCE_DIR) / "configs" / "sod.yaml").string());
  EXPECT_EQ(rc, 0) << log;
  EXPECT_NE(log.find("first step 0.000845 s (about 237 steps to 0.2 s at that step)"), std::string::npos) << log;
  EXPECT_NE(log.find("snapshots about 19 KiB each (94 KiB for 5 of them)"), std::string::npos) << log;
  // Twice the cells: half the step, twice the steps and the snapshot.
  std::tie(rc, log) = run_shell(dir, bin("cosim").string() + " check " +
                                         (fs::path(COSIM_SOURCE_DIR) / "configs" / "sod.yaml").string() +
                                         " --set 'fluid.mesh.cells=[800]'");
  EXPECT_NE(log.find("first step 0.000423 s (about 474 steps"), std::string::npos) << log;
  EXPECT_NE(log.find("snapshots about 38 KiB each"), std::string::npos) << log;
}

// cosim check --fluid-ranks N states the layout the ranks will take and each rank's share: the 200 x 200 particle
// blast on 3 ranks is split along y (the least cut area, slow axes first on ties) into blocks of 200 x 67 and
// 200 x 66 cells; a layout the scene fixes is stated as such, and one that does not fit the ranks is refused as the
// run would refuse it, naming the key.
TEST(SceneCheck, ThePlanStatesTheLayoutOfTheFluidsRanks) {
  const fs::path dir = test_dir("check_plan_ranks");
  const std::string check =
      bin("cosim").string() + " check " + (fs::path(COSIM_SOURCE_DIR) / "configs" / "particle_blast_2d.yaml").string();
  auto [rc, log] = run_shell(dir, check + " --fluid-ranks 3");
  EXPECT_EQ(rc, 0) << log;
  EXPECT_NE(log.find("ranks: 3, layout 1 x 3 (the least cut area), the largest block 200 x 67 cells (13400; the "
                     "smallest 13200), state about "),
            std::string::npos)
      << log;
  std::tie(rc, log) = run_shell(dir, check + " --fluid-ranks 3 --set 'fluid.parallel.ranks=[3, 1]'");
  EXPECT_EQ(rc, 0) << log;
  EXPECT_NE(log.find("ranks: 3, layout 3 x 1 (fluid.parallel.ranks), the largest block 67 x 200 cells"),
            std::string::npos)
      << log;
  std::tie(rc, log) = run_shell(dir, check + " --fluid-ranks 3 --set 'fluid.parallel.ranks=[2, 1]'");
  EXPECT_EQ(rc, 2) << log;
  EXPECT_NE(log.find("fluid.parallel.ranks [2, 1]"), std::string::npos) << log;
  // One rank: no ranks line.
  std::tie(rc, log) = run_shell(dir, check);
  EXPECT_EQ(rc, 0) << log;
  EXPECT_EQ(log.find("ranks:"), std::string::npos) << log;
}

// cosim check --solid-ranks N states the METIS parts the solid's ranks will compute (owned elements per rank near
// an equal share of the 27000 Sedov elements, the halo elements and ghost nodes a rank reads), and refuses what the
// ranks would refuse: the conforming panel's ALE air runs on one rank only.
TEST(SceneCheck, ThePlanStatesThePartsOfTheSolidsRanks) {
  const fs::path dir = test_dir("check_plan_solid_ranks");
  const fs::path configs = fs::path(COSIM_SOURCE_DIR) / "configs";
  auto [rc, log] = run_shell(dir, bin("cosim").string() + " check " + (configs / "solid_sedov_lulesh.yaml").string() +
                                      " --solid-ranks 3 --set 'solid.mesh.cells=[12, 12, 12]'");
  EXPECT_EQ(rc, 0) << log;
  const std::size_t at = log.find("solid ranks: 3 (METIS parts, ");
  ASSERT_NE(at, std::string::npos) << log;
  int fewest = 0, most = 0;
  const std::size_t owned = log.find("owned elements ", at);
  ASSERT_NE(owned, std::string::npos) << log;
  ASSERT_EQ(std::sscanf(log.c_str() + owned, "owned elements %d to %d per rank", &fewest, &most), 2) << log;
  EXPECT_LE(fewest, 576);  // 1728 / 3
  EXPECT_GE(most, 576);
  EXPECT_LE(most, 576 * 1.05) << "METIS parts within 5% of an equal share";
  std::tie(rc, log) = run_shell(dir, bin("cosim").string() + " check " +
                                         (configs / "shock_panel_2d_conforming.yaml").string() + " --solid-ranks 2");
  EXPECT_EQ(rc, 2) << log;
  EXPECT_NE(log.find("ALE blocks (solid.ale.blocks) run on one rank only"), std::string::npos) << log;
}

// The coupled cycle: the blast on the steel panel has the fluid's first step 3.64e-6 s and the solid's stable step
// 9.67e-7 s (its elements are 0.02 m of 4340 steel, c about 5 km/s): the solid's step sets the first cycle's; with
// 10 solid substeps per cycle the fluid's step does.
TEST(SceneCheck, ThePlanStatesTheCoupledCyclesStepAndItsNumber) {
  const fs::path dir = test_dir("check_plan_coupled");
  const std::string cmd =
      bin("cosim").string() + " check " + (fs::path(COSIM_SOURCE_DIR) / "configs" / "shock_panel_2d.yaml").string();
  auto [rc, log] = run_shell(dir, cmd);
  EXPECT_EQ(rc, 0) << log;
  EXPECT_NE(log.find("first stable step 9.67e-07 s"), std::string::npos) << log;
  EXPECT_NE(log.find("coupled: first cycle's step 9.67e-07 s (the solid's stable step), about 1035 cycles to 0.001 s"),
            std::string::npos)
      << log;
  EXPECT_EQ(log.find("plan-facts"), std::string::npos) << log;  // the figures' line is cosim's, not the user's
  std::tie(rc, log) = run_shell(dir, cmd + " --set solid.numerics.max_subcycles=10");
  EXPECT_NE(log.find("coupled: first cycle's step 3.64e-06 s (the fluid's step), about 275 cycles"), std::string::npos)
      << log;
  std::tie(rc, log) = run_shell(dir, cmd + " --set coupling.time.dt_max=5e-7");
  EXPECT_NE(log.find("coupled: first cycle's step 5e-07 s (coupling.time.dt_max), about 2000 cycles"),
            std::string::npos)
      << log;
}

TEST(SceneCheck, TheCoupledEstimateNamesWhatLimitsTheStep) {
  using cosim::launcher::coupled_estimate;
  const nlohmann::json facts = {{"coupler", {{"end_time", 1.0}, {"dt_max", 0.0}}},
                                {"fluid_solver", {{"first_step", 0.01}}},
                                {"solid_solver", {{"first_step", 0.004}, {"max_subcycles", 4}}}};
  EXPECT_EQ(coupled_estimate(facts),
            "coupled: first cycle's step 0.01 s (the fluid's step), about 100 cycles to 1 s at "
            "that step (the step follows the flow)");
  nlohmann::json rigid = facts;  // a rigid solid has no step of its own; a replaced one says nothing
  rigid["solid_solver"].erase("first_step");
  rigid["fluid_solver"]["first_step"] = 0.3;
  EXPECT_EQ(coupled_estimate(rigid).rfind("coupled: first cycle's step 0.3 s (the fluid's step), about 4 cycles", 0),
            0u);
  EXPECT_EQ(coupled_estimate(nlohmann::json::object()), "");
}
