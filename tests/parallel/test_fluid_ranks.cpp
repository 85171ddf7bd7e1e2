// fluid_solver on several ranks: the snapshots equal the one-rank run's bit for bit (the Godunov update is local and
// the step a minimum), the summary says the ranks and their layout were real, a set written on N ranks restarts on
// M, and a failure on one rank ends every rank with that rank's message and code.
#include <gtest/gtest.h>

#include <csignal>
#include <cstring>
#include <thread>

#include "tests/parallel/rank_runs.h"

namespace {

using cosim::test::expect_stopped_rank_named;
using cosim::test::RankRun;
using cosim::test::run_fluid_ranks;
using cosim::test::run_then_restart;
using cosim::test::scene_path;
using cosim::test::scratch_path;
using cosim::test::series_difference;
using cosim::test::summary_of;

// Every boundary kind besides periodic (the other scenes'), one phase, the low-Mach correction.
const char* kInflowWallBox = R"(name: inflow_wall_box
fluid:
  mesh: {cells: [36, 27], lower: [0.0, 0.0], upper: [1.0, 0.75]}
  phases: [{name: air, material: air}]
  numerics: {low_mach: true}
  time: {end: 4.0e-4}
  boundaries:
    x_lower: {type: inflow, state: {rho: 1.5, velocity: [120.0, 0.0], p: 1.6e5}}
    x_upper: transmissive
    y_lower: wall
    y_upper: wall
  initial:
    state: {rho: 1.2, velocity: [0.0, 0.0], p: 1.0e5}
    regions:
      - box: {lower: [0.45, 0.15], upper: [0.75, 0.45]}
        state: {rho: 3.0, velocity: [0.0, 30.0], p: 3.0e5}
  output: {interval: 2.0e-4}
)";

struct Case {
  std::string name, scene, sets;
  std::vector<int> ranks;
  int dim;
};

std::vector<Case> cases() {
  return {
      {"sod", scene_path("sod"), "", {2, 3, 4}, 1},
      {"water_air", scene_path("water_air_shock_tube"), "--set fluid.mesh.cells=[120]", {2, 3, 4}, 1},
      {"particle_blast",
       scene_path("particle_blast_2d"),
       "--set fluid.mesh.cells=[40,40] --set fluid.time.end=2.0e-4 --set fluid.output.interval=1.0e-4",
       {2, 3, 4},
       2},
      {"gresho",
       scene_path("gresho_vortex"),
       "--set fluid.mesh.cells=[24,24] --set fluid.time.end=0.1 --set fluid.output.interval=0.05",
       {2, 3, 4},
       2},
      {"inflow_wall_box", cosim::test::write_scene("inflow_wall_box", kInflowWallBox), "", {2, 3, 4}, 2},
      {"density_wave",
       scene_path("density_wave_3d"),
       "--set fluid.mesh.cells=[10,10,10] --set fluid.time.end=0.05 --set fluid.output.interval=0.025",
       {2, 3, 4},
       3},
  };
}

// The layout the summary reports: as many blocks as ranks, over the mesh's axes only.
void expect_real_ranks(const nlohmann::json& s, int ranks, int dim, const std::string& what) {
  ASSERT_TRUE(s.contains("parallel")) << what;
  const nlohmann::json& p = s["parallel"];
  EXPECT_EQ(p["ranks"].get<int>(), ranks) << what;
  const auto layout = p["layout"].get<std::vector<int>>();
  ASSERT_EQ(static_cast<int>(layout.size()), dim) << what;
  int product = 1;
  for (int b : layout) product *= b;
  EXPECT_EQ(product, ranks) << what;
  if (ranks > 1) { EXPECT_GT(p["halo_bytes"].get<double>(), 0.0) << what << ": no ghost layer crossed between ranks"; }
  EXPECT_EQ(p["threads_per_rank"].get<int>(), 1) << what;
}

TEST(FluidRanks, SnapshotsEqualTheOneRankRunBitForBit) {
  for (const Case& c : cases()) {
    const auto one = scratch_path(c.name + "_1");
    const RankRun r1 = run_fluid_ranks(1, c.scene, one, c.sets);
    ASSERT_EQ(r1.code, 0) << c.name << "\n" << r1.log;
    expect_real_ranks(summary_of(one), 1, c.dim, c.name);
    for (int n : c.ranks) {
      const auto out = scratch_path(c.name + "_" + std::to_string(n));
      const RankRun r = run_fluid_ranks(n, c.scene, out, c.sets);
      ASSERT_EQ(r.code, 0) << c.name << " on " << n << " ranks\n" << r.log;
      const nlohmann::json s = summary_of(out);
      expect_real_ranks(s, n, c.dim, c.name);
      EXPECT_EQ(series_difference(one, out), "") << c.name << " on " << n << " ranks";
      const nlohmann::json s1 = summary_of(one);
      EXPECT_EQ(s["steps"], s1["steps"]) << c.name;
      // Totals are sums over the ranks' blocks, in another order than one rank's: equal to round-off.
      for (std::size_t k = 0; k < s1["totals"]["end"].size(); ++k) {
        const double m1 = s1["totals"]["end"][k]["mass"].get<double>(),
                     mn = s["totals"]["end"][k]["mass"].get<double>();
        EXPECT_NEAR(mn, m1, 1e-13 * std::abs(m1)) << c.name;
      }
      std::printf("[ measured ] %s on %d ranks (layout %s): bit for bit, %.2f s (one rank %.2f s)\n", c.name.c_str(), n,
                  s["parallel"]["layout"].dump().c_str(), r.seconds, r1.seconds);
    }
  }
}

TEST(FluidRanks, TheScenesLayoutIsUsedOrRefusedNamingTheKey) {
  const std::string sets = "--set fluid.mesh.cells=[24,24] --set fluid.time.end=0.05 --set fluid.output.interval=0.05";
  const auto one = scratch_path("layout_1");
  ASSERT_EQ(run_fluid_ranks(1, scene_path("gresho_vortex"), one, sets).code, 0);
  const auto out = scratch_path("layout_1x3");
  const RankRun r = run_fluid_ranks(3, scene_path("gresho_vortex"), out, sets + " --set fluid.parallel.ranks=[1,3]");
  ASSERT_EQ(r.code, 0) << r.log;
  EXPECT_EQ(summary_of(out)["parallel"]["layout"], nlohmann::json({1, 3}));
  EXPECT_EQ(series_difference(one, out), "");
  const auto bad = scratch_path("layout_bad");
  const RankRun refused =
      run_fluid_ranks(3, scene_path("gresho_vortex"), bad, sets + " --set fluid.parallel.ranks=[2,2]");
  EXPECT_EQ(refused.code, 2) << refused.log;
  EXPECT_NE(refused.log.find("fluid.parallel.ranks [2, 2]: 2 x 2 x 1 blocks make 4 ranks, but the run has 3"),
            std::string::npos)
      << refused.log;
  EXPECT_FALSE(std::filesystem::exists(bad / "summary.json"));
}

// A set written on N ranks restarts on M and ends as the uninterrupted run, bit for bit.
TEST(FluidRanks, ACheckpointRestartsOnAnotherRankCount) {
  const std::string sets =
      "--set fluid.mesh.cells=[40,40] --set fluid.time.end=2.0e-4 --set fluid.output.interval=5.0e-5 "
      "--set 'fluid.checkpoint={interval: 1.0e-4, keep: 2}'";
  const std::string scene = scene_path("particle_blast_2d");
  const auto whole = scratch_path("restart_whole");
  ASSERT_EQ(run_fluid_ranks(1, scene, whole, sets).code, 0);
  for (const auto& [from, to] : std::vector<std::pair<int, int>>{{2, 3}, {3, 1}}) {
    const std::string tag = std::to_string(from) + "_to_" + std::to_string(to);
    const auto first =
        run_then_restart("fluid_solver", scene, sets, "--set fluid.time.end=1.0e-4", from, to, "restart_" + tag);
    if (first.empty()) continue;
    EXPECT_EQ(series_difference(whole, first), "") << tag;
    EXPECT_EQ(summary_of(first)["parallel"]["ranks"].get<int>(), to);
    std::printf("[ measured ] checkpoint of %d ranks restarted on %d: bit for bit\n", from, to);
  }
}

// Water pulled apart in the middle block only cavitates there: rank 1 of 3 names the cell, every rank stops with
// code 3 within seconds, and the summary names the rank.
TEST(FluidRanks, ABadStateOnOneRankStopsEveryRankWithItsMessage) {
  const std::string scene = cosim::test::write_scene("cavitation", R"(name: cavitation
fluid:
  mesh: {cells: [150], lower: [0.0], upper: [1.5]}
  phases: [{name: water, material: water}]
  time: {end: 1.0e-4}
  initial:
    state: {rho: 1000.0, velocity: [0.0], p: 1.0e5}
    regions:
      - box: {lower: [0.5], upper: [0.75]}
        state: {rho: 1000.0, velocity: [-2000.0], p: 1.0e5}
      - box: {lower: [0.75], upper: [1.0]}
        state: {rho: 1000.0, velocity: [2000.0], p: 1.0e5}
  output: {interval: 1.0e-6}
)");
  const auto out = scratch_path("cavitation_3");
  const RankRun r = run_fluid_ranks(3, scene, out, "", 60);
  EXPECT_EQ(r.code, 3) << r.log;
  EXPECT_LT(r.seconds, 20.0) << r.log;
  EXPECT_NE(r.log.find("rank 1 of 3: inadmissible state in cell (i=7"), std::string::npos) << r.log;
  const nlohmann::json s = summary_of(out);
  EXPECT_EQ(s["status"], "failed");
  EXPECT_EQ(s["parallel"]["failed_rank"].get<int>(), 1);
  EXPECT_NE(s["error"].get<std::string>().find("inadmissible state"), std::string::npos);
  for (const auto& f : std::filesystem::directory_iterator(out)) EXPECT_NE(f.path().extension(), ".tmp");
  std::printf("[ measured ] a bad state on rank 1 of 3 ended the run in %.2f s with code %d\n", r.seconds, r.code);
}

// The checkpoint root cannot be written (a file stands where its folder should be): rank 0's I/O error ends every
// rank with code 4.
TEST(FluidRanks, AnIoErrorOnRankZeroStopsEveryRankWithCodeFour) {
  const auto out = scratch_path("io_error");
  const auto blocker = scratch_path("io_error_blocker");
  std::ofstream(blocker) << "not a folder\n";
  const RankRun r =
      run_fluid_ranks(2, scene_path("sod"), out,
                      "--set 'fluid.checkpoint={interval: 0.05}' --checkpoints " + (blocker / "sets").string(), 60);
  EXPECT_EQ(r.code, 4) << r.log;
  EXPECT_NE(r.log.find("rank 0 of 2"), std::string::npos) << r.log;
  EXPECT_EQ(summary_of(out)["parallel"]["failed_rank"].get<int>(), 0);
}

// The 2-rank Gresho run of the failure tests, with `pkill -SIGNAL` sent to its newest rank once its first snapshot is
// written (by pattern, not matching this shell); the run and the seconds from the signal to the run's end.
std::pair<RankRun, double> run_with_a_signalled_rank(const std::filesystem::path& out, const std::string& signal) {
  std::chrono::steady_clock::time_point sent_at;
  std::thread sender([&] {
    for (int i = 0; i < 200; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      if (std::filesystem::exists(out / "fluid_000000.h5")) break;
    }
    sent_at = std::chrono::steady_clock::now();
    const std::string cmd = "pkill -" + signal + " -n -f 'fluid_solve[r] .*--out " + out.string() + " '";
    EXPECT_EQ(std::system(cmd.c_str()), 0);
  });
  const RankRun r = run_fluid_ranks(2, scene_path("gresho_vortex"), out,
                                    "--set fluid.mesh.cells=[200,200] --set fluid.output.interval=0.01", 120);
  const auto ended = std::chrono::steady_clock::now();
  sender.join();
  return {r, std::chrono::duration<double>(ended - sent_at).count()};
}

// kill -9 of one rank: mpirun ends the others, the run returns non-zero within 5 s.
TEST(FluidRanks, AKilledRankEndsTheRunWithinFiveSeconds) {
  const auto [r, after_kill] = run_with_a_signalled_rank(scratch_path("killed"), "9");
  EXPECT_NE(r.code, 0) << r.log;
  EXPECT_LT(after_kill, 5.0) << r.log;
  std::printf("[ measured ] one of 2 ranks killed: the run ended with code %d %.2f s after the kill\n", r.code,
              after_kill);
}

}  // namespace

// SIGSTOP of one rank (silent, not dead: mpirun does not notice): the rank watchdog of the other rank does, within
// 5 s; code 5, the silent rank and the one that noticed it named in summary.json, no rank left behind. (Which rank
// is stopped depends on which process started last.)
TEST(FluidRanks, AStoppedRankEndsTheRunWithinFiveSeconds) {
  const auto out = scratch_path("stopped");
  const auto [r, after_stop] = run_with_a_signalled_rank(out, "STOP");
  EXPECT_LT(after_stop, 5.0) << r.log;
  expect_stopped_rank_named("fluid_solver", out, r);
  std::printf("[ measured ] one of 2 ranks stopped (SIGSTOP): the run ended with code %d %.2f s after the stop\n",
              r.code, after_stop);
}

// cosim run --fluid-ranks N starts a fluid-only scene on N ranks (mpirun before fluid_solver in launch.json) with
// the one-rank run's snapshots; fluid ranks for a scene without a fluid are refused before anything starts.
TEST(FluidRanks, CosimRunStartsTheFluidOnRanks) {
  const std::string cosim = std::string(COSIM_BINARY_DIR) + "/bin/cosim";
  if (!std::filesystem::exists(cosim)) GTEST_SKIP() << "cosim is not built (COSIM_BUILD_COUPLING off)";
  const auto one = scratch_path("cosim_ranks_1"), two = scratch_path("cosim_ranks_2");
  const std::string scene = scene_path("sod");
  ASSERT_EQ(std::system((cosim + " run " + scene + " --quiet --out " + one.string() + " > /dev/null 2>&1").c_str()), 0);
  const std::string cmd =
      cosim + " run " + scene + " --quiet --fluid-ranks 2 --out " + two.string() + " > " + two.string() + ".log 2>&1";
  ASSERT_EQ(WEXITSTATUS(std::system(cmd.c_str())), 0) << cosim::test::read_text(two.string() + ".log");
  EXPECT_EQ(series_difference(one / "fluid", two / "fluid"), "");
  EXPECT_EQ(summary_of(two / "fluid")["parallel"]["ranks"].get<int>(), 2);
  const nlohmann::json launch = nlohmann::json::parse(cosim::test::read_text(two / "launch.json"));
  EXPECT_EQ(launch["commands"]["fluid"][0], "mpirun");
  const auto refused = scratch_path("cosim_ranks_no_fluid");
  const std::string solid_only = cosim + " run " + scene_path("solid_piston_1d") + " --quiet --fluid-ranks 2 --out " +
                                 refused.string() + " > " + refused.string() + ".log 2>&1";
  EXPECT_EQ(WEXITSTATUS(std::system(solid_only.c_str())), 2);
  EXPECT_NE(cosim::test::read_text(refused.string() + ".log").find("2 fluid ranks: a solid-only run has no fluid"),
            std::string::npos)
      << cosim::test::read_text(refused.string() + ".log");
  EXPECT_FALSE(std::filesystem::exists(refused / "solid"));
}
