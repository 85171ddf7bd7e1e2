// solid_solver on several ranks (mpirun, oversubscribed on this machine's cores): the snapshots and block history of
// 2 and 3 ranks equal the one-rank run's bit for bit, the energy totals to round-off (summed over ranks); the summary
// proves the ranks were real; failures end every rank with the failing rank named.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "tests/parallel/rank_runs.h"

using cosim::test::expect_stopped_rank_named;
using cosim::test::RankRun;
using cosim::test::read_text;
using cosim::test::run_solid_ranks;
using cosim::test::run_then_restart;
using cosim::test::scene_path;
using cosim::test::scratch_path;
using cosim::test::series_difference;
using cosim::test::summary_of;

namespace {

// The elastic plate of tests/solid/test_waves_plasticity.cpp (uniaxial strain: a velocity step on x_lower of a
// laterally confined steel-like plate), run to 0.75 m / c_L.
const char* kElasticPlate = R"(name: elastic_plate
solid:
  mesh: {cells: [400, 1], lower: [0, 0], upper: [1.0, 0.0025]}
  blocks:
    - name: plate
      eos: {type: linear_elastic, bulk_modulus: 1.6e11}
      density: 7800.0
      strength: {shear_modulus: 8.0e10}
  boundaries:
    - {set: x_lower, type: velocity, vx: 1.0}
    - {set: y_lower, type: symmetry}
    - {set: y_upper, type: symmetry}
  time: {end: 1.28e-4}
  output: {interval: 4.0e-5, history_every: 10}
)";

// configs/shock_panel_2d_conforming.yaml without its ALE line: a Lagrangian air (ALE runs on one rank only).
std::string panel_without_ale() {
  std::string text = read_text(scene_path("shock_panel_2d_conforming"));
  const std::string ale = "  ale: {blocks: [air, hot_air]}\n";
  const auto at = text.find(ale);
  EXPECT_NE(at, std::string::npos) << "the ALE line of shock_panel_2d_conforming.yaml moved";
  if (at != std::string::npos) text.erase(at, ale.size());
  return cosim::test::write_scene("shock_panel_lagrangian", text);
}

struct Case {
  std::string name, scene, sets;
};

std::vector<Case> cases() {
  return {
      {"sedov", scene_path("solid_sedov_lulesh"),
       "--set solid.mesh.cells=[12,12,12] --set solid.time.end=2.0e-3 --set solid.output.interval=1.0e-3"},
      {"elastic_plate", cosim::test::write_scene("elastic_plate", kElasticPlate), ""},
      // The conforming panel with a Lagrangian air: it holds to 3e-5 s (it tangles at 6.5e-5 s).
      {"shock_panel_lagrangian", panel_without_ale(), "--set solid.time.end=3.0e-5 --set solid.output.interval=1.5e-5"},
      // The rigid piston [-1, 0] m of 40 of the 160 elements, across the parts of 2 and 3 ranks.
      {"rigid_piston", scene_path("solid_piston_1d"), "--set solid.time.end=0.01 --set solid.output.interval=0.005"},
  };
}

// The parallel block: as many ranks as started, every element owned once, halos exchanged.
void expect_real_ranks(const nlohmann::json& s, int ranks, const std::string& what) {
  ASSERT_TRUE(s.contains("parallel")) << what;
  const nlohmann::json& p = s["parallel"];
  EXPECT_EQ(p["ranks"].get<int>(), ranks) << what;
  EXPECT_EQ(p["layout"].get<std::string>(), "metis") << what;
  const auto elements = p["elements_per_rank"].get<std::vector<long>>();
  const auto nodes = p["nodes_per_rank"].get<std::vector<long>>();
  ASSERT_EQ(static_cast<int>(elements.size()), ranks) << what;
  long ne = 0, nn = 0;
  for (int r = 0; r < ranks; ++r) {
    EXPECT_GT(elements[r], 0) << what << ": rank " << r << " owns no element";
    ne += elements[r];
    nn += nodes[r];
  }
  EXPECT_EQ(ne, s["elements"].get<long>()) << what;
  EXPECT_EQ(nn, s["nodes"].get<long>()) << what;
  EXPECT_GT(p["halo_bytes"].get<double>(), 0.0) << what << ": no ghost node crossed between ranks";
  EXPECT_GT(p["cut_faces"].get<long>(), 0) << what;
  EXPECT_EQ(p["threads_per_rank"].get<int>(), 1) << what;
}

// Energy totals summed over ranks: the one-rank values to round-off of the total (the ranks sum their shares).
void expect_energy_close(const nlohmann::json& a, const nlohmann::json& b, const std::string& what) {
  const double scale = std::abs(a["energy"]["start"]["total"].get<double>()) + 1e-300;
  for (const char* k : {"internal", "kinetic", "total", "boundary_work"}) {
    const double x = a["energy"]["end"][k].get<double>(), y = b["energy"]["end"][k].get<double>();
    EXPECT_LE(std::abs(x - y), 1e-12 * scale) << what << ": energy " << k << " " << x << " vs " << y;
  }
}

TEST(SolidRanks, SnapshotsEqualTheOneRankRunBitForBit) {
  for (const Case& c : cases()) {
    const auto one = scratch_path("solid_" + c.name + "_1");
    const RankRun r1 = run_solid_ranks(1, c.scene, one, c.sets);
    ASSERT_EQ(r1.code, 0) << c.name << "\n" << r1.log;
    const nlohmann::json s1 = summary_of(one);
    for (int n : {2, 3}) {
      const std::string what = c.name + " on " + std::to_string(n) + " ranks";
      const auto out = scratch_path("solid_" + c.name + "_" + std::to_string(n));
      const RankRun r = run_solid_ranks(n, c.scene, out, c.sets);
      ASSERT_EQ(r.code, 0) << what << "\n" << r.log;
      EXPECT_EQ(series_difference(one, out, "solid_"), "") << what;
      EXPECT_EQ(read_text(one / "block_history.csv"), read_text(out / "block_history.csv")) << what;
      const nlohmann::json s = summary_of(out);
      EXPECT_EQ(s["steps"].get<long>(), s1["steps"].get<long>()) << what;
      EXPECT_EQ(s["final_time"].get<double>(), s1["final_time"].get<double>()) << what;
      EXPECT_EQ(s.value("rigid_bodies", nlohmann::json()).dump(17), s1.value("rigid_bodies", nlohmann::json()).dump(17))
          << what;  // centre of mass and velocity, bit for bit
      expect_energy_close(s1, s, what);
      expect_real_ranks(s, n, what);
      std::printf("[ measured ] %s: %zu snapshots equal bit for bit, %ld cut faces, %.1f s (one rank %.1f s)\n",
                  what.c_str(), cosim::test::snapshots_of(out, "solid_").size(), s["parallel"]["cut_faces"].get<long>(),
                  r.seconds, r1.seconds);
    }
  }
}

// The piston's elements lie on more than one rank: its force and moment are the sum of several ranks' nodes.
TEST(SolidRanks, TheRigidPistonSpansRanks) {
  const auto out = scratch_path("solid_rigid_piston_span");
  const RankRun r = run_solid_ranks(3, scene_path("solid_piston_1d"), out,
                                    "--set solid.time.end=1.0e-3 --set solid.output.interval=1.0e-3");
  ASSERT_EQ(r.code, 0) << r.log;
  const auto spans = summary_of(out)["parallel"]["rigid_body_ranks"].get<std::vector<int>>();
  ASSERT_EQ(spans.size(), 1u);
  EXPECT_GE(spans[0], 2);
}

// A set written on 2 ranks restarts on 3 (and one of 3 on 1) and ends as the uninterrupted one-rank run, bit for bit
// (snapshots and block history), its energy totals to round-off.
TEST(SolidRanks, ACheckpointRestartsOnAnotherRankCount) {
  const std::string sets =
      "--set solid.mesh.cells=[10,10,10] --set solid.time.end=2.0e-3 --set solid.output.interval=5.0e-4 "
      "--set 'solid.checkpoint={interval: 1.0e-3, keep: 2}'";
  const std::string scene = scene_path("solid_sedov_lulesh");
  const auto whole = scratch_path("solid_restart_whole");
  const RankRun w = run_solid_ranks(1, scene, whole, sets);
  ASSERT_EQ(w.code, 0) << w.log;
  for (const auto& [from, to] : std::vector<std::pair<int, int>>{{2, 3}, {3, 1}}) {
    const std::string tag = std::to_string(from) + "_to_" + std::to_string(to);
    const auto first =
        run_then_restart("solid_solver", scene, sets, "--set solid.time.end=1.0e-3", from, to, "solid_restart_" + tag);
    if (first.empty()) continue;
    EXPECT_EQ(series_difference(whole, first, "solid_"), "") << tag;
    EXPECT_EQ(read_text(whole / "block_history.csv"), read_text(first / "block_history.csv")) << tag;
    const nlohmann::json s = summary_of(first), s1 = summary_of(whole);
    EXPECT_EQ(s["parallel"]["ranks"].get<int>(), to) << tag;
    EXPECT_EQ(s["steps"].get<long>(), s1["steps"].get<long>()) << tag;
    expect_energy_close(s1, s, "restarted " + tag);
    std::printf("[ measured ] a solid checkpoint of %d ranks restarted on %d: bit for bit\n", from, to);
  }
}

TEST(SolidRanks, AleBlocksAreRefusedOnSeveralRanks) {
  const auto out = scratch_path("solid_ale_refused");
  const RankRun r = run_solid_ranks(2, scene_path("shock_panel_2d_conforming"), out);
  EXPECT_EQ(r.code, 2) << r.log;
  EXPECT_NE(r.log.find("ALE blocks (solid.ale.blocks) run on one rank only"), std::string::npos) << r.log;
  EXPECT_FALSE(std::filesystem::exists(out / "summary.json"));
}

// A line of nodes pushed at up to 100 km/s (a velocity boundary ramped over 0.1 ms, which the first stable step
// does not see) inverts the elements next to it on whichever rank owns them: code 3, that rank named in the log and
// in summary.json with the element, no temporary file left.
TEST(SolidRanks, ABadStateOnOneRankStopsEveryRankWithItsMessage) {
  const std::string scene = cosim::test::write_scene("solid_crash", R"(name: solid_crash
solid:
  mesh: {cells: [30, 6], lower: [0.0, 0.0], upper: [3.0, 0.6]}
  blocks:
    - name: gas
      eos: {type: ideal_gas, gamma: 1.4}
      density: 1.0
      initial: {pressure: 1.0e5}
  boundaries:
    - {set: x_lower, type: fixed}
    - {set: x_upper, type: fixed}
    - {box: {lower: [2.2, 0.0], upper: [2.2, 0.6]}, type: velocity, vx: 1.0e5, ramp: 1.0e-4}
  time: {end: 1.0e-2}
  output: {interval: 1.0e-2}
)");
  const auto out = scratch_path("solid_crash_3");
  const RankRun r = run_solid_ranks(3, scene, out, "", 60);
  EXPECT_EQ(r.code, 3) << r.log;
  const nlohmann::json s = summary_of(out);
  EXPECT_EQ(s["status"].get<std::string>(), "failed");
  const int failed = s["parallel"]["failed_rank"].get<int>();
  EXPECT_NE(r.log.find("rank " + std::to_string(failed) + " of 3: element 22 of block 'gas' inverted"),
            std::string::npos)
      << r.log;
  EXPECT_NE(s["error"].get<std::string>().find("inverted"), std::string::npos) << s.dump();
  EXPECT_NE(s["error"].get<std::string>().find("(rank " + std::to_string(failed) + " of 3, "), std::string::npos)
      << s.dump();
  EXPECT_LT(r.seconds, 20.0) << r.log;
  for (const auto& f : std::filesystem::directory_iterator(out)) EXPECT_NE(f.path().extension(), ".tmp");
  std::printf("[ measured ] a bad state on rank %d of 3 ended the run in %.2f s with code %d\n", failed, r.seconds,
              r.code);
}

}  // namespace

// SIGSTOP of one rank of 2: the other rank's watchdog notices within 5 s; code 5, the silent rank and the one that
// noticed it named in summary.json, no rank left behind.
TEST(SolidRanks, AStoppedRankEndsTheRunWithinFiveSeconds) {
  const auto out = scratch_path("solid_stopped");
  std::chrono::steady_clock::time_point sent_at;
  std::thread sender([&] {
    for (int i = 0; i < 300; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      if (std::filesystem::exists(out / "solid_000000.h5")) break;
    }
    sent_at = std::chrono::steady_clock::now();
    const std::string cmd = "pkill -STOP -n -f 'solid_solve[r] .*--out " + out.string() + " '";
    EXPECT_EQ(std::system(cmd.c_str()), 0);
  });
  const RankRun r = run_solid_ranks(2, scene_path("solid_sedov_lulesh"), out,
                                    "--set solid.mesh.cells=[24,24,24] --set solid.output.interval=0.005", 120);
  const auto ended = std::chrono::steady_clock::now();
  sender.join();
  const double after_stop = std::chrono::duration<double>(ended - sent_at).count();
  EXPECT_LT(after_stop, 5.0) << r.log;
  expect_stopped_rank_named("solid_solver", out, r);
  std::printf("[ measured ] one of 2 solid ranks stopped (SIGSTOP): the run ended with code %d %.2f s after the stop\n",
              r.code, after_stop);
}

// cosim run --solid-ranks N starts a solid-only scene on N ranks (mpirun before solid_solver in launch.json) with the
// one-rank run's snapshots; a coupled scene whose solid has ALE blocks (the conforming panel) is refused before
// anything starts, and so is solid_solver on 2 ranks with a coupler address on that scene (before it connects).
TEST(SolidRanks, CosimRunStartsTheSolidOnRanks) {
  const std::string cosim = std::string(COSIM_BINARY_DIR) + "/bin/cosim";
  if (!std::filesystem::exists(cosim)) GTEST_SKIP() << "cosim is not built (COSIM_BUILD_COUPLING off)";
  const auto one = scratch_path("cosim_solid_ranks_1"), two = scratch_path("cosim_solid_ranks_2");
  const std::string scene = scene_path("solid_piston_1d"),
                    sets = " --set solid.time.end=0.005 --set solid.output.interval=0.0025";
  ASSERT_EQ(
      std::system((cosim + " run " + scene + sets + " --quiet --out " + one.string() + " > /dev/null 2>&1").c_str()),
      0);
  const std::string cmd = cosim + " run " + scene + sets + " --quiet --solid-ranks 2 --out " + two.string() + " > " +
                          two.string() + ".log 2>&1";
  ASSERT_EQ(WEXITSTATUS(std::system(cmd.c_str())), 0) << read_text(two.string() + ".log");
  EXPECT_EQ(series_difference(one / "solid", two / "solid", "solid_"), "");
  EXPECT_EQ(summary_of(two / "solid")["parallel"]["ranks"].get<int>(), 2);
  const nlohmann::json launch = nlohmann::json::parse(read_text(two / "launch.json"));
  EXPECT_EQ(launch["commands"]["solid"][0].get<std::string>(), "mpirun");
  const auto refused = scratch_path("cosim_solid_ranks_coupled_ale");
  std::filesystem::remove_all(refused);
  const std::string coupled = cosim + " run " + scene_path("shock_panel_2d_conforming") +
                              " --quiet --solid-ranks 2 --out " + refused.string() + " > " + refused.string() +
                              ".log 2>&1";
  EXPECT_EQ(WEXITSTATUS(std::system(coupled.c_str())), 2);
  const std::string log = read_text(refused.string() + ".log");
  EXPECT_NE(log.find("2 ranks: ALE blocks (solid.ale.blocks) run on one rank only"), std::string::npos) << log;
  EXPECT_NE(log.find("nothing was started"), std::string::npos) << log;
  EXPECT_FALSE(std::filesystem::exists(refused / "solid")) << log;
  // solid_solver itself, on 2 ranks with a coupler address: refused before it connects.
  const auto direct = scratch_path("solid_ranks_coupled_direct");
  const RankRun r =
      run_solid_ranks(2, scene_path("shock_panel_2d_conforming"), direct, "--coupler ipc:///tmp/nowhere.sock", 60);
  EXPECT_EQ(r.code, 2) << r.log;
  EXPECT_NE(
      r.log.find("cannot set up the coupled solid on 2 ranks: ALE blocks (solid.ale.blocks) run on one rank only"),
      std::string::npos)
      << r.log;
}
