// A coupled run whose fluid runs on several MPI ranks (cosim run --fluid-ranks N): each block cuts the interface over
// its cells and samples the faces centred in it, rank 0 talks to the coupler for all. The fluid, solid and interface
// snapshots and the interface history equal the one-rank run's bit for bit: the piston on 2 and 3 ranks in 2D and on
// 2 in 3D, the modified Sod problem, the steel panel and the tungsten blast at small sizes on 2 to 4, the piston and
// the steel panel with the conservative embedded boundary on 2 and 3; a set written on 2 fluid ranks restarts on 3
// and ends as the uninterrupted run; a stopped fluid rank ends the run,
// named in run_summary.json. The fluid's summary proves the ranks were real (ranks and layout) and records the relay's
// traffic on every rank; the coupler records the ranks each solver's Hello speaks for.
#include <gtest/gtest.h>

#include <chrono>
#include <nlohmann/json.hpp>
#include <thread>

#include "common/checkpoint/checkpoint_sets.h"
#include "coupled_test_util.h"
#include "run_compare.h"

using namespace cosim::test;

namespace {

void expect_fluid_ranks(const fs::path& run, int ranks, const std::vector<int>& layout) {
  const nlohmann::json s = nlohmann::json::parse(read_text(run / "fluid" / "summary.json"));
  EXPECT_EQ(s["status"].get<std::string>(), "completed");
  EXPECT_EQ(s["parallel"]["ranks"].get<int>(), ranks) << s.dump();
  EXPECT_EQ(s["parallel"]["layout"].get<std::vector<int>>(), layout) << s.dump();
  // The relay's record: every rank got every message rank 0 relayed (at least a directive, the faces and the states
  // per cycle) and every rank's samples in each cycle's gather, so the bytes are alike on every rank.
  const nlohmann::json& relay = s["parallel"]["relay"];
  ASSERT_TRUE(relay.is_object()) << s.dump();
  const long cycles = s["coupling"]["cycles"].get<long>();
  EXPECT_GE(relay["relayed"]["messages"].get<long>(), 3 * cycles) << relay.dump();
  EXPECT_EQ(relay["samples"]["gathers"].get<long>(), cycles) << relay.dump();
  for (const char* part : {"relayed", "samples"}) {
    const auto bytes = relay[part]["bytes"].get<std::vector<double>>();
    ASSERT_EQ(bytes.size(), static_cast<std::size_t>(ranks)) << relay.dump();
    EXPECT_GT(bytes[0], 0) << relay.dump();
    for (double b : bytes) EXPECT_EQ(b, bytes[0]) << part << ": " << relay.dump();
  }
  const nlohmann::json launch = nlohmann::json::parse(read_text(run / "launch.json"));
  EXPECT_EQ(launch["commands"]["fluid"][0].get<std::string>(), "mpirun") << launch.dump();
  const nlohmann::json run_summary = nlohmann::json::parse(read_text(run / "run_summary.json"));
  for (const auto& p : run_summary["processes"])
    if (p["name"] == "fluid") { EXPECT_EQ(p["ranks"].get<int>(), ranks) << run_summary.dump(); }
}

}  // namespace

TEST(CoupledRanks, ThePistonOnFluidRanksEqualsTheOneRankRun) {
  const std::string args = "--set coupling.time.end=0.04 --set coupling.output.interval=0.01";
  const fs::path one = run_dir("ranks_piston_1");
  ASSERT_EQ(cosim_run(scene_file("piston_2d"), one, args), 0) << run_logs(one);
  expect_coupler_peer_ranks(one, 1, 1);
  for (const int ranks : {2, 3}) {
    const fs::path many = run_dir("ranks_piston_" + std::to_string(ranks));
    ASSERT_EQ(cosim_run(scene_file("piston_2d"), many, args + " --fluid-ranks " + std::to_string(ranks)), 0)
        << run_logs(many);
    expect_fluid_ranks(many, ranks, {ranks, 1});
    expect_coupler_peer_ranks(many, ranks, 1);  // Hello.ranks of the fluid's rank 0, for all of them
    expect_same_runs(one, many, 5);
    EXPECT_EQ(read_text(one / "coupler" / "interface_history.csv"),
              read_text(many / "coupler" / "interface_history.csv"));
  }
}

TEST(CoupledRanks, The3DPistonOnTwoFluidRanksEqualsTheOneRankRun) {
  const std::string args = "--set coupling.time.end=0.02 --set coupling.output.interval=0.005";
  const fs::path one = run_dir("ranks_piston3d_1"), two = run_dir("ranks_piston3d_2");
  ASSERT_EQ(cosim_run(scene_file("piston_3d"), one, args), 0) << run_logs(one);
  ASSERT_EQ(cosim_run(scene_file("piston_3d"), two, args + " --fluid-ranks 2"), 0) << run_logs(two);
  expect_fluid_ranks(two, 2, {2, 1, 1});
  expect_same_runs(one, two, 5);
  EXPECT_EQ(read_text(one / "coupler" / "interface_history.csv"), read_text(two / "coupler" / "interface_history.csv"));
}

// The paper's coupled scenes at small sizes: the modified Sod problem (9.4) on 2 and 4 fluid ranks (blocks 1 x 2 and
// 2 x 2), the steel panel (9.5) on 3 (1 x 3: the panel's faces sampled by different blocks) and the tungsten blast
// (9.6, two phases, 3D) on 2.
TEST(CoupledRanks, ThePapersScenesOnFluidRanksEqualTheOneRankRun) {
  struct Case {
    std::string scene, args;
    std::vector<std::vector<int>> layouts;  // per rank count 2, 3, ... as used below
    std::vector<int> ranks;
    int snapshots;
  };
  const std::vector<Case> cases = {
      {"modified_sod_2d",
       "--set 'fluid.mesh.cells=[64,64]' --set 'solid.mesh.cells=[16,16]'",
       {{1, 2}, {2, 2}},
       {2, 4},
       3},
      {"shock_panel_2d", "--set coupling.time.end=4e-4 --set coupling.output.interval=5e-5", {{1, 3}}, {3}, 8},
      {"tungsten_blast_3d",
       "--set 'fluid.mesh.cells=[24,24,24]' --set 'solid.mesh.cells=[2,6,6]' --set coupling.time.end=1.2e-4 "
       "--set coupling.output.interval=3e-5",
       {{1, 1, 2}},
       {2},
       4}};
  for (const Case& c : cases) {
    const fs::path one = run_dir("ranks_" + c.scene + "_1");
    ASSERT_EQ(cosim_run(scene_file(c.scene), one, c.args), 0) << run_logs(one);
    for (std::size_t i = 0; i < c.ranks.size(); ++i) {
      const fs::path many = run_dir("ranks_" + c.scene + "_" + std::to_string(c.ranks[i]));
      ASSERT_EQ(cosim_run(scene_file(c.scene), many, c.args + " --fluid-ranks " + std::to_string(c.ranks[i])), 0)
          << run_logs(many);
      expect_fluid_ranks(many, c.ranks[i], c.layouts[i]);
      expect_same_runs(one, many, c.snapshots);
      EXPECT_EQ(read_text(one / "coupler" / "interface_history.csv"),
                read_text(many / "coupler" / "interface_history.csv"))
          << c.scene << " on " << c.ranks[i] << " fluid ranks";
    }
  }
}

// The conservative embedded boundary (fluid.embedded.conservative) on fluid ranks: the volumes the cells' contents
// fill and the covered and uncovered cells' exchanges cross the block seams as on one rank, bit for bit: the moving
// piston on 2 (blocks 2 x 1, its wall crossing cells every cycle) and the steel panel on 3 (1 x 3).
TEST(CoupledRanks, TheConservativeBoundaryOnFluidRanksEqualsTheOneRankRun) {
  struct Case {
    std::string scene, args;
    int ranks;
    std::vector<int> layout;
    int snapshots;
  };
  const std::string conservative = " --set fluid.embedded.conservative=true";
  const std::vector<Case> cases = {
      {"piston_2d", "--set coupling.time.end=0.04 --set coupling.output.interval=0.01", 2, {2, 1}, 5},
      {"shock_panel_2d", "--set coupling.time.end=4e-4 --set coupling.output.interval=5e-5", 3, {1, 3}, 8}};
  for (const Case& c : cases) {
    const fs::path one = run_dir("ranks_conservative_" + c.scene + "_1");
    ASSERT_EQ(cosim_run(scene_file(c.scene), one, c.args + conservative), 0) << run_logs(one);
    const nlohmann::json s1 = nlohmann::json::parse(read_text(one / "fluid" / "summary.json"));
    ASSERT_TRUE(s1["embedded"]["conservative"].get<bool>()) << c.scene;
    const fs::path many = run_dir("ranks_conservative_" + c.scene + "_" + std::to_string(c.ranks));
    ASSERT_EQ(cosim_run(scene_file(c.scene), many, c.args + conservative + " --fluid-ranks " + std::to_string(c.ranks)),
              0)
        << run_logs(many);
    expect_fluid_ranks(many, c.ranks, c.layout);
    expect_same_runs(one, many, c.snapshots);
    EXPECT_EQ(read_text(one / "coupler" / "interface_history.csv"),
              read_text(many / "coupler" / "interface_history.csv"))
        << c.scene << " on " << c.ranks << " fluid ranks";
  }
}

// Checkpoints written by 2 fluid ranks (every rank its block of one part), the run resumed from the first set on 3.
TEST(CoupledRanks, ASetOfTwoFluidRanksRestartsOnThree) {
  const std::string args = "--set coupling.time.end=0.04 --set coupling.checkpoint.interval=0.015";
  const fs::path full = run_dir("ranks_restart_full"), resumed = run_dir("ranks_restart_resumed");
  ASSERT_EQ(cosim_run(scene_file("piston_2d"), full, args + " --fluid-ranks 2"), 0) << run_logs(full);
  const auto sets = cosim::checkpoint::complete_sets(full / "checkpoints");
  ASSERT_GE(sets.size(), 1u) << "no checkpoint set written";
  fs::copy(full, resumed, fs::copy_options::recursive);
  const std::string cmd = bin("cosim").string() + " run " + scene_file("piston_2d").string() + " --restart " +
                          resumed.string() + " --from " + std::to_string(sets.front().cycle) + " --quiet " + args +
                          " --fluid-ranks 3 > " + resumed.string() + ".log 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << read_text(resumed.string() + ".log") << run_logs(resumed);
  expect_fluid_ranks(resumed, 3, {3, 1});
  expect_same_runs(full, resumed, 3);
}

// SIGSTOP of one fluid rank of 2 in a coupled run (silent, not dead): the other rank's watchdog notices, the fluid
// ends with code 5, the coupler stops the solid, and run_summary.json names the fluid and the silent rank, all within
// 5 s of the stop; no process of the run is left.
TEST(CoupledRanks, AStoppedFluidRankEndsTheCoupledRunNamingTheRank) {
  const fs::path out = run_dir("ranks_stopped");
  std::chrono::steady_clock::time_point sent_at;
  std::thread stopper([&] {
    for (int i = 0; i < 600; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      if (fs::exists(out / "fluid" / "fluid_000001.h5")) break;
    }
    sent_at = std::chrono::steady_clock::now();
    const std::string cmd = "pkill -STOP -n -f 'fluid_solve[r] .*--out " + (out / "fluid").string() + " '";
    EXPECT_EQ(std::system(cmd.c_str()), 0);
  });
  const int rc = cosim_run(scene_file("piston_2d"), out, "--fluid-ranks 2 --set coupling.output.interval=0.01");
  const auto ended = std::chrono::steady_clock::now();
  stopper.join();
  const double after_stop = std::chrono::duration<double>(ended - sent_at).count();
  EXPECT_NE(rc, 0) << run_logs(out);
  EXPECT_LT(after_stop, 5.0) << run_logs(out);
  const nlohmann::json s = nlohmann::json::parse(read_text(out / "run_summary.json"));
  EXPECT_EQ(s["status"].get<std::string>(), "failed") << s.dump(2);
  const nlohmann::json& f = s["failed_process"];
  EXPECT_EQ(f["name"].get<std::string>(), "fluid") << s.dump(2);
  ASSERT_TRUE(f.contains("rank")) << s.dump(2);
  const int silent = f["rank"].get<int>();
  EXPECT_TRUE(silent == 0 || silent == 1) << s.dump(2);
  EXPECT_EQ(f["noticed_by"].get<int>(), 1 - silent) << s.dump(2);
  EXPECT_NE(f["error"].get<std::string>().find("rank " + std::to_string(silent) + " of 2 has been silent"),
            std::string::npos)
      << s.dump(2);
  for (const char* p : {"fluid_solve[r]", "solid_solve[r]", "couple[r]"})
    EXPECT_NE(std::system(("pgrep -f '" + std::string(p) + " .*" + out.string() + "' > /dev/null").c_str()), 0)
        << p << " was left behind";
  std::printf("[ measured ] one of 2 coupled fluid ranks stopped: the run ended %.2f s after the stop (rank %d)\n",
              after_stop, silent);
}
