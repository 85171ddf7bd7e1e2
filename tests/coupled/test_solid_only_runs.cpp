// Every scene of the catalogue runs through `cosim run`: a scene without fluid: is a solid-only run of solid_solver
// alone, with the launcher's run directory, logs and summary, and the same outputs as solid_solver run by hand.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "coupled_test_util.h"
#include "run_compare.h"

using namespace cosim::test;

TEST(SolidOnlyRuns, ASceneWithoutFluidRunsTheSolidAloneWithTheOutputsOfSolidSolver) {
  const std::string args = "--set solid.time.end=0.05";
  const fs::path dir = run_dir("solid_only"), by_hand = run_dir("solid_only_by_hand");
  ASSERT_EQ(cosim_run(scene_file("solid_piston_1d"), dir, args), 0) << run_logs(dir);
  const nlohmann::json summary = nlohmann::json::parse(read_text(dir / "run_summary.json"));
  EXPECT_EQ(summary["status"], "completed") << summary.dump(2);
  ASSERT_TRUE(summary.contains("processes")) << summary.dump(2);
  EXPECT_EQ(summary["processes"].size(), 1u) << summary.dump(2);
  EXPECT_TRUE(fs::exists(dir / "solid.log"));
  EXPECT_FALSE(fs::exists(dir / "fluid")) << "no fluid in a solid-only run";
  EXPECT_FALSE(fs::exists(dir / "coupler"));
  // The same scene by hand: the same snapshots and histories, bit for bit.
  fs::create_directories(by_hand);
  const std::string cmd = bin("solid_solver").string() + " " + scene_file("solid_piston_1d").string() + " --out " +
                          (by_hand / "solid").string() + " --quiet " + args + " > " + by_hand.string() + ".log 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << read_text(fs::path(by_hand.string() + ".log"));
  expect_same_runs(dir, by_hand, 5);
}

TEST(SolidOnlyRuns, CosimCheckStatesASolidOnlyRunAndRefusesWhatCannotBeOne) {
  const fs::path dir = run_dir("solid_only_check");
  fs::create_directories(dir);
  const auto check = [&](const std::string& scene_args, const std::string& name) {
    const std::string cmd = bin("cosim").string() + " check " + scene_args + " > " + (dir / name).string() + " 2>&1";
    const int rc = std::system(cmd.c_str());
    return std::pair{WIFEXITED(rc) ? WEXITSTATUS(rc) : -1, read_text(dir / name)};
  };
  for (const char* scene : {"shock_panel_2d_conforming", "solid_sedov_lulesh", "solid_piston_1d"}) {
    const auto [rc, out] = check(scene_file(scene).string(), std::string(scene) + ".txt");
    EXPECT_EQ(rc, 0) << out;
    EXPECT_NE(out.find("valid; a solid-only run of the solid"), std::string::npos) << out;
    EXPECT_NE(out.find("solid: "), std::string::npos) << out;  // solid_solver's plan
  }
  // Neither fluid nor solid; a coupling: section without a fluid.
  std::ofstream(dir / "empty.yaml") << "name: empty\n";
  const auto [none, none_out] = check((dir / "empty.yaml").string(), "none.txt");
  EXPECT_EQ(none, 2) << none_out;
  EXPECT_NE(none_out.find("a fluid: or a solid: section"), std::string::npos) << none_out;
  std::ofstream(dir / "no_fluid.yaml") << read_text(scene_file("solid_piston_1d")) << "coupling:\n  time: {end: 1}\n";
  const auto [nf, nf_out] = check((dir / "no_fluid.yaml").string(), "no_fluid.txt");
  EXPECT_EQ(nf, 2) << nf_out;
  EXPECT_NE(nf_out.find("no coupling: section in a scene without fluid:"), std::string::npos) << nf_out;
  // cosim writes no checkpoints of a solid-only run: a restart of one is refused before anything starts.
  const std::string restart = bin("cosim").string() + " run " + scene_file("solid_piston_1d").string() + " --restart " +
                              dir.string() + " > " + (dir / "restart.txt").string() + " 2>&1";
  EXPECT_EQ(WEXITSTATUS(std::system(restart.c_str())), 2);
  EXPECT_NE(read_text(dir / "restart.txt").find("a solid-only run, which writes no checkpoints through cosim"),
            std::string::npos)
      << read_text(dir / "restart.txt");
}
