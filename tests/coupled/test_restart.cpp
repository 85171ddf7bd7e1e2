// Whole-run checkpoint and restart (coupling.checkpoint, fluid.checkpoint; cosim run --restart RUN [--from N]):
// a run resumed from a checkpoint set gives the uninterrupted run's outputs bit for bit (snapshots, XDMF indices,
// interface and block histories, the cycles of timing.csv); also after every process was killed with SIGKILL
// between two sets. A set one of whose parts is missing or corrupt is never used, and a restart with a changed
// physics key is refused.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "common/checkpoint/checkpoint_sets.h"
#include "coupled_test_util.h"
#include "run_compare.h"
#include "tests/support/flip_bit.h"

using namespace cosim::test;

namespace {

std::vector<cosim::checkpoint::SetInfo> sets_of(const fs::path& run) {
  return cosim::checkpoint::complete_sets(run / "checkpoints");
}

// Every row of the run's timing.csv accounts its wall time: no cycle after the first, the ones with snapshots and
// checkpoints included, shows more solver, output and coupler work than wall time (negative communication) beyond
// 2 ms of clock granularity and scheduling (before outputs had their column: down to -11 ms after each snapshot; a
// fresh-clone run beside other builds, load average about 5, showed -1.06 ms in one cycle of the tungsten restart).
// The first cycle holds the solvers' set-up, whose start the coupler knows only as the moment it read their Hello
// (up to a poll interval late: -1.5 ms seen with the Python piston), so it is left out.
void expect_timing_accounts_the_wall(const fs::path& run) {
  std::istringstream in(read_text(run / "coupler" / "timing.csv"));
  std::string line;
  std::getline(in, line);
  ASSERT_EQ(line, "cycle,wall,solid,fluid,coupler,output,comm");
  double worst = 0;
  long rows = 0, worst_cycle = -1;
  while (std::getline(in, line)) {
    std::vector<double> v;
    std::istringstream fields(line);
    for (std::string f; std::getline(fields, f, ',');) v.push_back(std::stod(f));
    ASSERT_EQ(v.size(), 7u) << line;
    ++rows;
    EXPECT_GE(v[5], 0.0) << line;
    if (v[0] > 0 && v[6] < worst) worst = v[6], worst_cycle = static_cast<long>(v[0]);
  }
  std::printf("%s: %ld timing rows, least communication %.3g s (cycle %ld)\n", run.filename().c_str(), rows, worst,
              worst_cycle);
  EXPECT_GT(worst, -2e-3) << "cycle " << worst_cycle;
}

// Runs `scene` to its end with checkpoints (`args`), then resumes a copy of the run from its first complete set and
// compares the two: the copy's outputs after the set are rewritten by the restarted processes.
void expect_restart_reproduces(const std::string& name, const std::string& scene, const std::string& args,
                               int min_snapshots) {
  const fs::path full = run_dir(name + "_full"), resumed = run_dir(name + "_resumed");
  ASSERT_EQ(cosim_run(scene_file(scene), full, args), 0) << run_logs(full);
  if (fs::exists(full / "coupler")) expect_timing_accounts_the_wall(full);
  const auto sets = sets_of(full);
  ASSERT_GE(sets.size(), 1u) << "no checkpoint set written";
  fs::copy(full, resumed, fs::copy_options::recursive);
  const long from = sets.front().cycle;
  // The resumed run's later outputs are removed first: what it has at the end it wrote itself.
  const std::string cmd = bin("cosim").string() + " run " + scene_file(scene).string() + " --restart " +
                          resumed.string() + " --from " + std::to_string(from) + " --quiet " + args + " > " +
                          resumed.string() + ".log 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << read_text(resumed.string() + ".log") << run_logs(resumed);
  std::printf("%s: restarted from the set of cycle/step %ld at t = %.6g s (of %zu)\n", name.c_str(), from,
              sets.front().time, sets.size());
  expect_same_runs(full, resumed, min_snapshots);
}

}  // namespace

TEST(Restart, CoupledPistonResumedFromACheckpointIsTheUninterruptedRunBitForBit) {
  expect_restart_reproduces("piston", "piston_2d",
                            "--set coupling.time.end=0.1 --set coupling.checkpoint.interval=0.04", 20);
}

TEST(Restart, ConservativeBoundaryResumedFromACheckpointIsTheUninterruptedRunBitForBit) {
  // embedded.conservative: the cells' contents belong to the fluid volumes of the time the state has reached (a step
  // after the checkpoint's geometry), which the restart restores with the cycle's step; the piston uncovers and
  // covers cells on both sides after the set (at 0.04 s).
  expect_restart_reproduces("conservative_piston", "piston_2d",
                            "--set coupling.time.end=0.06 --set coupling.checkpoint.interval=0.04 "
                            "--set fluid.embedded.conservative=true",
                            6);
}

TEST(Restart, LightPistonResumedFromACheckpointIsTheUninterruptedRunBitForBit) {
  // The light piston is a deformable gas block: nodal state, element history and the Robin impedances.
  expect_restart_reproduces("light_piston", "piston_light_2d",
                            "--set coupling.time.end=0.02 --set coupling.checkpoint.interval=0.008", 6);
}

TEST(Restart, SteelPanelWithPlasticityResumedFromACheckpointIsTheUninterruptedRunBitForBit) {
  // Paper 9.4: deviatoric stresses, plastic strain and work, clamped edges, the ghost-fluid boundary deforming. The
  // set at 0.2 ms is taken while the panel yields (plastic work from 0.13 ms on).
  expect_restart_reproduces("shock_panel", "shock_panel_2d",
                            "--set coupling.time.end=4e-4 --set coupling.output.interval=5e-5 "
                            "--set coupling.checkpoint.interval=2e-4",
                            12);
}

TEST(Restart, TungstenBlast3DResumedFromACheckpointIsTheUninterruptedRunBitForBit) {
  // Paper 9.6 at a small size: 3D embedded boundary of a deforming hex target, two phases with a granular temperature.
  expect_restart_reproduces("tungsten", "tungsten_blast_3d",
                            "--set 'fluid.mesh.cells=[24,24,24]' --set 'solid.mesh.cells=[2,6,6]' "
                            "--set coupling.time.end=1.2e-4 --set coupling.output.interval=3e-5 "
                            "--set coupling.checkpoint.interval=6e-5",
                            8);
}

TEST(Restart, ThePythonPistonCheckpointsAndResumesThroughTheProtocolAlone) {
  // An outside solver (python/rigid_piston.py) in place of solid_solver: its own part, solid.json.
  const std::string exe = "/usr/bin/python3 " + (fs::path(COSIM_BINARY_DIR) / "python" / "rigid_piston.py").string();
  expect_restart_reproduces(
      "python_piston", "piston_2d",
      "--solid-exe '" + exe + "' --set coupling.time.end=0.06 --set coupling.checkpoint.interval=0.025", 7);
}

TEST(Restart, TwoPhaseFluidOnlyRunResumedFromACheckpointIsTheUninterruptedRunBitForBit) {
  // Air and dispersed tungsten with drag, heat exchange and the granular temperature.
  expect_restart_reproduces("particle_blast", "particle_blast_2d",
                            "--set 'fluid.mesh.cells=[48,48]' --set fluid.time.end=2e-4 "
                            "--set fluid.output.interval=5e-5 --set fluid.checkpoint.cycles=40",
                            4);
}

TEST(Restart, AfterEveryProcessIsKilledTheRestartEndsInTheUninterruptedState) {
  const std::string args = "--set coupling.time.end=0.1 --set coupling.checkpoint.interval=0.02";
  const fs::path full = run_dir("killed_full"), killed = run_dir("killed");
  ASSERT_EQ(cosim_run(scene_file("piston_2d"), full, args), 0) << run_logs(full);
  // The same run, all four processes killed (SIGKILL, as a node failure) once a set is complete.
  const std::string run = bin("cosim").string() + " run " + scene_file("piston_2d").string() + " --out " +
                          killed.string() + " --quiet " + args + " > " + killed.string() + ".log 2>&1 &";
  ASSERT_EQ(std::system(run.c_str()), 0);
  bool have_set = false;
  for (int i = 0; i < 600 && !have_set; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    have_set = !sets_of(killed).empty();
  }
  ASSERT_TRUE(have_set) << "no checkpoint set within 12 s";
  std::this_thread::sleep_for(std::chrono::milliseconds(150));  // past the set: later outputs exist
  // ("[-]-out" matches the processes' "--out", not this command's own shell)
  const std::string kill = "pkill -9 -f -- '[-]-out " + killed.string() + "'";
  ASSERT_EQ(std::system(kill.c_str()), 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  ASSERT_FALSE(fs::exists(killed / "run_summary.json") &&
               read_text(killed / "run_summary.json").find("completed") != std::string::npos)
      << "the run ended before it was killed";
  const std::string resume = bin("cosim").string() + " run " + scene_file("piston_2d").string() + " --restart " +
                             killed.string() + " --quiet " + args + " > " + killed.string() + ".resume.log 2>&1";
  ASSERT_EQ(std::system(resume.c_str()), 0) << read_text(killed.string() + ".resume.log") << run_logs(killed);
  expect_same_runs(full, killed, 10);
}

TEST(Restart, AnIncompleteSetIsNeverUsed) {
  const std::string args = "--set coupling.time.end=0.1 --set coupling.checkpoint.interval=0.03";
  const fs::path dir = run_dir("incomplete");
  ASSERT_EQ(cosim_run(scene_file("piston_2d"), dir, args), 0) << run_logs(dir);
  auto sets = sets_of(dir);
  ASSERT_EQ(sets.size(), 2u);  // keep: 2 (of 3 written)
  // The newest set loses the solid's part, as if the solid died while writing it.
  fs::remove(sets.back().dir / "solid.h5");
  ASSERT_EQ(sets_of(dir).size(), 1u);
  const std::string base = bin("cosim").string() + " run " + scene_file("piston_2d").string() + " --restart " +
                           dir.string() + " --quiet " + args;
  // Asked for by number, the incomplete set is refused with the reason.
  const int rc = std::system(
      (base + " --from " + std::to_string(sets.back().cycle) + " > " + dir.string() + ".r2.log 2>&1").c_str());
  EXPECT_EQ(WEXITSTATUS(rc), 2);
  EXPECT_NE(read_text(dir.string() + ".r2.log").find("solid.h5, which is missing"), std::string::npos)
      << read_text(dir.string() + ".r2.log");
  // Otherwise the restart takes the newest complete set.
  EXPECT_EQ(std::system((base + " > " + dir.string() + ".r.log 2>&1").c_str()), 0)
      << read_text(dir.string() + ".r.log");
  const std::string log = read_text(dir.string() + ".r.log");
  EXPECT_NE(log.find("checkpoint of cycle " + std::to_string(sets.front().cycle)), std::string::npos) << log;
}

TEST(Restart, ACorruptPartIsRefusedByNameAndTheRestartTakesTheNewestIntactSet) {
  const std::string args = "--set coupling.time.end=0.1 --set coupling.checkpoint.interval=0.03";
  const fs::path full = run_dir("corrupt_full"), dir = run_dir("corrupt");
  ASSERT_EQ(cosim_run(scene_file("piston_2d"), full, args), 0) << run_logs(full);
  fs::copy(full, dir, fs::copy_options::recursive);
  const auto sets = sets_of(dir);
  ASSERT_EQ(sets.size(), 2u);
  // One bit of the coupler's part flipped (its pressure predictor and histories are near the end of the file).
  cosim::test::flip_bit(sets.back().dir / "coupler.h5", -200);
  const std::string base = bin("cosim").string() + " run " + scene_file("piston_2d").string() + " --restart " +
                           dir.string() + " --quiet " + args;
  // Asked for by number, the set is refused, naming the part; nothing starts.
  const int rc = std::system(
      (base + " --from " + std::to_string(sets.back().cycle) + " > " + dir.string() + ".r2.log 2>&1").c_str());
  const std::string refused = read_text(dir.string() + ".r2.log");
  EXPECT_EQ(WEXITSTATUS(rc), 2) << refused;
  EXPECT_NE(refused.find("coupler.h5: SHA-256"), std::string::npos) << refused;
  EXPECT_NE(refused.find("the part is corrupt"), std::string::npos) << refused;
  // The coupler started by hand on that set refuses it too: a process never restores a part that fails.
  const std::string by_hand = bin("coupler").string() + " " + scene_file("piston_2d").string() + " --out " +
                              (dir / "by_hand").string() + " --endpoint ipc://" + (dir / "by_hand.sock").string() +
                              " --restart " + sets.back().dir.string() + " > " + dir.string() + ".c.log 2>&1";
  EXPECT_EQ(WEXITSTATUS(std::system(by_hand.c_str())), 2) << read_text(dir.string() + ".c.log");
  EXPECT_NE(read_text(dir.string() + ".c.log").find("the part is corrupt"), std::string::npos)
      << read_text(dir.string() + ".c.log");
  fs::remove_all(dir / "by_hand");
  // Otherwise the restart says which set it skipped and why, takes the older one and ends as the full run.
  ASSERT_EQ(std::system((base + " > " + dir.string() + ".r.log 2>&1").c_str()), 0)
      << read_text(dir.string() + ".r.log") << run_logs(dir);
  const std::string log = read_text(dir.string() + ".r.log");
  EXPECT_NE(log.find("skipping a checkpoint set that cannot be used: " + (sets.back().dir / "coupler.h5").string()),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("checkpoint of cycle " + std::to_string(sets.front().cycle)), std::string::npos) << log;
  expect_same_runs(full, dir, 10);
}

TEST(Restart, AChangedPhysicsKeyIsRefusedAndALaterEndTimeAllowed) {
  const std::string args = "--set coupling.time.end=0.06 --set coupling.checkpoint.interval=0.03";
  const fs::path dir = run_dir("changed");
  ASSERT_EQ(cosim_run(scene_file("piston_2d"), dir, args), 0) << run_logs(dir);
  const std::string base = bin("cosim").string() + " run " + scene_file("piston_2d").string() + " --restart " +
                           dir.string() + " --quiet --set coupling.checkpoint.interval=0.03 ";
  const int rc = std::system(
      (base + "--set coupling.time.end=0.06 --set solid.blocks.0.density=50 > " + dir.string() + ".c.log 2>&1")
          .c_str());
  const std::string log = read_text(dir.string() + ".c.log");
  EXPECT_EQ(WEXITSTATUS(rc), 2) << log;
  EXPECT_NE(log.find("solid.blocks[0].density: was 100.0, now 50"), std::string::npos) << log;
  // The end time may move: the run goes on from its last set to the new end.
  ASSERT_EQ(std::system((base + "--set coupling.time.end=0.09 > " + dir.string() + ".e.log 2>&1").c_str()), 0)
      << read_text(dir.string() + ".e.log") << run_logs(dir);
  const nlohmann::json s = nlohmann::json::parse(read_text(dir / "coupler" / "coupler_summary.json"));
  EXPECT_NEAR(s["time"].get<double>(), 0.09, 1e-12);
  const History h = read_history(dir);
  ASSERT_GT(h.size(), 10u);
  for (std::size_t i = 1; i < h.size(); ++i) ASSERT_GT(h.t[i], h.t[i - 1]) << "history line " << i << " repeats a time";
}

TEST(Restart, AFreshRunIntoTheSameDirectoryStartsWithoutTheEarlierRunsSets) {
  const fs::path dir = run_dir("fresh_again");
  ASSERT_EQ(
      cosim_run(scene_file("piston_2d"), dir, "--set coupling.time.end=0.1 --set coupling.checkpoint.interval=0.03"), 0)
      << run_logs(dir);
  ASSERT_EQ(sets_of(dir).size(), 2u);
  const double newest_before = sets_of(dir).back().time;
  // A shorter run: its one set must not sit behind the earlier run's later ones.
  ASSERT_EQ(
      cosim_run(scene_file("piston_2d"), dir, "--set coupling.time.end=0.05 --set coupling.checkpoint.interval=0.03"),
      0)
      << run_logs(dir);
  const auto sets = sets_of(dir);
  ASSERT_EQ(sets.size(), 1u);
  EXPECT_NEAR(sets[0].time, 0.03, 1e-3);
  EXPECT_GT(newest_before, 0.08);
}

TEST(Restart, CosimCheckStatesTheCheckpointPlan) {
  const fs::path out = run_dir("check_plan");
  fs::create_directories(out);
  const std::string cmd = bin("cosim").string() + " check " + scene_file("piston_2d").string() +
                          " --set coupling.checkpoint.interval=0.05 > " + (out / "plan.txt").string() + " 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << read_text(out / "plan.txt");
  EXPECT_NE(read_text(out / "plan.txt").find("checkpoints every 0.05 s, newest 2 kept"), std::string::npos)
      << read_text(out / "plan.txt");
  // keep without a frequency says what is missing.
  const std::string bad = bin("cosim").string() + " check " + scene_file("piston_2d").string() +
                          " --set coupling.checkpoint.keep=3 > " + (out / "bad.txt").string() + " 2>&1";
  EXPECT_EQ(WEXITSTATUS(std::system(bad.c_str())), 2);
  EXPECT_NE(read_text(out / "bad.txt").find("interval [s] > 0 or cycles > 0"), std::string::npos)
      << read_text(out / "bad.txt");
}
