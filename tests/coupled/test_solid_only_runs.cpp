// Every scene of the catalogue runs through `cosim run`: a scene without fluid: is a solid-only run of solid_solver
// alone, with the launcher's run directory, logs and summary, and the same outputs as solid_solver run by hand.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "common/checkpoint/checkpoint_sets.h"
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
}

// A solid-only run with solid.checkpoint writes its sets into RUN/checkpoints like a fluid-only run, and
// `cosim run --restart RUN [--from CYCLE]` continues it from a set (here the older of the two), ending as the
// uninterrupted run bit for bit (also on another rank count: the sets hold the whole state).
TEST(SolidOnlyRuns, ACheckpointedSolidOnlyRunRestartsThroughCosim) {
  const std::string args = "--set solid.time.end=0.05 --set 'solid.checkpoint={interval: 0.012, keep: 2}'";
  const fs::path whole = run_dir("solid_only_whole"), cut = run_dir("solid_only_cut");
  ASSERT_EQ(cosim_run(scene_file("solid_piston_1d"), whole, args), 0) << run_logs(whole);
  ASSERT_EQ(cosim_run(scene_file("solid_piston_1d"), cut, args), 0) << run_logs(cut);
  const auto sets = cosim::checkpoint::complete_sets(cut / "checkpoints");
  ASSERT_EQ(sets.size(), 2u) << "keep: 2";
  // The last snapshot removed, as if the run had been killed before it: the restart must write it again.
  fs::path last;
  for (const auto& e : fs::directory_iterator(cut / "solid"))
    if (e.path().extension() == ".h5" && (last.empty() || e.path().filename() > last.filename())) last = e.path();
  ASSERT_FALSE(last.empty());
  fs::remove(last);
  const std::string restart = bin("cosim").string() + " run " + scene_file("solid_piston_1d").string() + " --restart " +
                              cut.string() + " --from " + std::to_string(sets.front().cycle) +
                              " --quiet --solid-ranks 2 " + args + " > " + cut.string() + ".restart.log 2>&1";
  ASSERT_EQ(WEXITSTATUS(std::system(restart.c_str())), 0) << read_text(fs::path(cut.string() + ".restart.log"));
  EXPECT_NE(read_text(fs::path(cut.string() + ".restart.log")).find("restarting from the checkpoint of cycle"),
            std::string::npos);
  EXPECT_TRUE(fs::exists(last)) << last;
  const nlohmann::json history = nlohmann::json::parse(read_text(cut / "run_history.json"));
  EXPECT_EQ(history["attempts"].size(), 2u) << history.dump(2);
  expect_same_runs(whole, cut, 5);
}
