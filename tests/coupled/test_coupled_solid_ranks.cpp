// A coupled run whose solid runs on several MPI ranks (cosim run --solid-ranks M), alone or with a fluid on ranks:
// rank 0 of the solid talks to the coupler for all, each rank updates its own nodes. The fluid, solid and interface
// snapshots and the interface history equal the one-rank run's bit for bit: the piston on (fluid, solid) ranks
// (1, 2), (3, 2) and (4, 1), the modified Sod problem (Robin and characteristic conditions), the steel panel (also
// read from a Gmsh file, by rank 0 alone) and the tungsten blast at small sizes; a set written on (1, 1) restarts on
// (2, 2) and one written on (2, 2) on (1, 1); a stopped or killed solid rank ends the run, named in run_summary.json.
// The solid's summary proves the ranks were real.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/types.h>

#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <thread>

#include "common/checkpoint/checkpoint_sets.h"
#include "coupled_test_util.h"
#include "run_compare.h"

using namespace cosim::test;

namespace {

std::string ranks_args(int fluid, int solid) {
  return " --fluid-ranks " + std::to_string(fluid) + " --solid-ranks " + std::to_string(solid);
}

// The solid's summary: M ranks of METIS parts that own every element between them, each some; the launcher started
// it under mpirun.
void expect_solid_ranks(const fs::path& run, int ranks) {
  const nlohmann::json s = nlohmann::json::parse(read_text(run / "solid" / "summary.json"));
  EXPECT_EQ(s["status"].get<std::string>(), "completed");
  const nlohmann::json& p = s["parallel"];
  ASSERT_TRUE(p.is_object()) << s.dump();
  EXPECT_EQ(p["ranks"].get<int>(), ranks) << s.dump();
  EXPECT_EQ(p["layout"].get<std::string>(), "metis") << s.dump();
  const auto owned = p["elements_per_rank"].get<std::vector<long>>();
  ASSERT_EQ(owned.size(), static_cast<std::size_t>(ranks)) << s.dump();
  long total = 0;
  for (long n : owned) {
    EXPECT_GT(n, 0) << s.dump();
    total += n;
  }
  EXPECT_EQ(total, s["elements"].get<long>()) << s.dump();
  const nlohmann::json launch = nlohmann::json::parse(read_text(run / "launch.json"));
  EXPECT_EQ(launch["commands"]["solid"][0].get<std::string>(), "mpirun") << launch.dump();
}

void expect_same_coupled_runs(const fs::path& one, const fs::path& many, int snapshots) {
  expect_same_runs(one, many, snapshots);
  EXPECT_EQ(read_text(one / "coupler" / "interface_history.csv"), read_text(many / "coupler" / "interface_history.csv"))
      << many;
}

}  // namespace

// The rigid piston (Robin conditions on a rigid block: the impedance sums over the body's nodes on every rank).
TEST(CoupledSolidRanks, ThePistonOnSolidRanksEqualsTheOneRankRun) {
  const std::string args = "--set coupling.time.end=0.04 --set coupling.output.interval=0.01";
  const fs::path one = run_dir("solid_ranks_piston_1_1");
  ASSERT_EQ(cosim_run(scene_file("piston_2d"), one, args), 0) << run_logs(one);
  for (const auto& [fluid, solid] : std::vector<std::pair<int, int>>{{1, 2}, {3, 2}, {4, 1}}) {
    const fs::path many = run_dir("solid_ranks_piston_" + std::to_string(fluid) + "_" + std::to_string(solid));
    ASSERT_EQ(cosim_run(scene_file("piston_2d"), many, args + ranks_args(fluid, solid)), 0) << run_logs(many);
    if (solid > 1) expect_solid_ranks(many, solid);
    expect_coupler_peer_ranks(many, fluid, solid);
    const nlohmann::json f = nlohmann::json::parse(read_text(many / "fluid" / "summary.json"));
    EXPECT_EQ(f["parallel"]["ranks"].get<int>(), fluid) << f.dump();
    expect_same_coupled_runs(one, many, 5);
  }
}

// The paper's coupled scenes at small sizes with the solid on ranks: the modified Sod problem (9.4, a deforming
// Lagrangian gas block) on (2, 2) and, under characteristic conditions (interface velocities imposed on the wetted
// nodes), on (1, 3); the steel panel (9.5) on (3, 2); the tungsten blast (9.6, 3D) on (2, 2).
TEST(CoupledSolidRanks, ThePapersScenesOnSolidRanksEqualTheOneRankRun) {
  struct Case {
    std::string scene, name, args;
    int fluid, solid, snapshots;
  };
  const std::string sod = "--set 'fluid.mesh.cells=[64,64]' --set 'solid.mesh.cells=[16,16]'";
  const std::vector<Case> cases = {
      {"modified_sod_2d", "sod", sod, 2, 2, 3},
      {"modified_sod_2d", "sod_characteristic", sod + " --set coupling.mode=characteristic", 1, 3, 3},
      {"shock_panel_2d", "panel", "--set coupling.time.end=4e-4 --set coupling.output.interval=5e-5", 3, 2, 8},
      {"tungsten_blast_3d", "blast",
       "--set 'fluid.mesh.cells=[24,24,24]' --set 'solid.mesh.cells=[2,6,6]' --set coupling.time.end=1.2e-4 "
       "--set coupling.output.interval=3e-5",
       2, 2, 4}};
  for (const Case& c : cases) {
    const fs::path one = run_dir("solid_ranks_" + c.name + "_1_1");
    ASSERT_EQ(cosim_run(scene_file(c.scene), one, c.args), 0) << run_logs(one);
    const fs::path many =
        run_dir("solid_ranks_" + c.name + "_" + std::to_string(c.fluid) + "_" + std::to_string(c.solid));
    ASSERT_EQ(cosim_run(scene_file(c.scene), many, c.args + ranks_args(c.fluid, c.solid)), 0) << run_logs(many);
    expect_solid_ranks(many, c.solid);
    expect_same_coupled_runs(one, many, c.snapshots);
  }
}

// The steel panel read from a Gmsh file (configs/shock_panel_2d_gmsh.yaml) with the solid on 2 ranks: rank 0 alone
// read the file and broadcast the mesh (the solid's summary says which ranks read it); the run equals the one-rank
// run bit for bit.
TEST(CoupledSolidRanks, TheGmshPanelOnSolidRanksEqualsTheOneRankRun) {
  const std::string args = "--set coupling.time.end=4e-4 --set coupling.output.interval=5e-5";
  const fs::path one = run_dir("solid_ranks_panel_gmsh_1_1"), two = run_dir("solid_ranks_panel_gmsh_1_2");
  ASSERT_EQ(cosim_run(scene_file("shock_panel_2d_gmsh"), one, args), 0) << run_logs(one);
  ASSERT_EQ(cosim_run(scene_file("shock_panel_2d_gmsh"), two, args + ranks_args(1, 2)), 0) << run_logs(two);
  expect_solid_ranks(two, 2);
  const nlohmann::json s = nlohmann::json::parse(read_text(two / "solid" / "summary.json"));
  ASSERT_TRUE(s["parallel"].contains("mesh")) << s.dump();
  EXPECT_EQ(s["parallel"]["mesh"]["read_by_ranks"].get<std::vector<int>>(), std::vector<int>{0}) << s.dump();
  EXPECT_GT(s["parallel"]["mesh"]["bytes"].get<double>(), 0.0) << s.dump();
  expect_same_coupled_runs(one, two, 8);
}

// Checkpoints of the steel panel written with (fluid, solid) ranks (1, 1), resumed from the first set on (2, 2), and
// the other way round: both end as the uninterrupted run.
TEST(CoupledSolidRanks, ASetRestartsOnOtherRankCountsBitForBit) {
  const std::string args =
      "--set coupling.time.end=4e-4 --set coupling.output.interval=5e-5 --set coupling.checkpoint.interval=1.5e-4";
  for (const auto& [from, to] : std::vector<std::pair<int, int>>{{1, 2}, {2, 1}}) {
    const std::string tag = std::to_string(from) + "_" + std::to_string(to);
    const fs::path full = run_dir("solid_ranks_restart_full_" + tag), resumed = run_dir("solid_ranks_restart_" + tag);
    ASSERT_EQ(cosim_run(scene_file("shock_panel_2d"), full, args + ranks_args(from, from)), 0) << run_logs(full);
    const auto sets = cosim::checkpoint::complete_sets(full / "checkpoints");
    ASSERT_GE(sets.size(), 1u) << "no checkpoint set written";
    fs::copy(full, resumed, fs::copy_options::recursive);
    const std::string cmd = bin("cosim").string() + " run " + scene_file("shock_panel_2d").string() + " --restart " +
                            resumed.string() + " --from " + std::to_string(sets.front().cycle) + " --quiet " + args +
                            ranks_args(to, to) + " > " + resumed.string() + ".log 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << read_text(resumed.string() + ".log") << run_logs(resumed);
    const nlohmann::json s = nlohmann::json::parse(read_text(resumed / "solid" / "summary.json"));
    EXPECT_EQ(s["coupling"]["restarted_from"].get<long>(), sets.front().cycle) << s.dump();
    if (to > 1) expect_solid_ranks(resumed, to);
    else EXPECT_FALSE(s.contains("parallel")) << s.dump();
    expect_same_coupled_runs(full, resumed, 8);
  }
}

// cosim check --solid-ranks M on a coupled scene states the solid's METIS parts; more ranks than elements is refused
// as the solid-only path refuses it, before anything starts.
TEST(CoupledSolidRanks, CosimCheckStatesTheLayoutAndRefusesMoreRanksThanElements) {
  const fs::path dir = run_dir("solid_ranks_check");
  fs::create_directories(dir);
  const std::string check = bin("cosim").string() + " check " + scene_file("piston_2d").string();
  const auto run_check = [&](int ranks) {
    const fs::path log = dir / (std::to_string(ranks) + ".log");
    const int rc =
        std::system((check + " --solid-ranks " + std::to_string(ranks) + " > " + log.string() + " 2>&1").c_str());
    return std::make_pair(WIFEXITED(rc) ? WEXITSTATUS(rc) : -1, read_text(log));
  };
  auto [rc, log] = run_check(2);
  EXPECT_EQ(rc, 0) << log;
  EXPECT_NE(log.find("solid ranks: 2 (METIS parts, "), std::string::npos) << log;
  EXPECT_NE(log.find("owned elements 4 to 4 per rank"), std::string::npos) << log;  // the piston's 8 elements
  std::tie(rc, log) = run_check(9);
  EXPECT_EQ(rc, 2) << log;
  EXPECT_NE(log.find("9 parts of a mesh of 8 elements: at least one element per part"), std::string::npos) << log;
}

namespace {

// The process of solid rank `rank` of the run in `out` (its MPI environment says which), or 0.
pid_t solid_rank_process(const fs::path& out, int rank) {
  const std::string cmd = "pgrep -f '^" + bin("solid_solver").string() + " .*--out " + (out / "solid").string() + " '";
  FILE* p = ::popen(cmd.c_str(), "r");
  if (!p) return 0;
  pid_t found = 0;
  const std::string key = std::string(1, '\0') + "OMPI_COMM_WORLD_RANK=" + std::to_string(rank) + '\0';
  for (long pid; std::fscanf(p, "%ld", &pid) == 1;)
    if ((std::string(1, '\0') + read_text("/proc/" + std::to_string(pid) + "/environ")).find(key) != std::string::npos)
      found = static_cast<pid_t>(pid);
  ::pclose(p);
  return found;
}

// The coupled piston with its solid on 2 ranks, solid rank `rank` sent `signal` once the solid's first snapshot is
// written: cosim's exit code and the seconds from the signal to the end of the run.
std::pair<int, double> signal_a_solid_rank(const fs::path& out, int rank, int signal) {
  std::chrono::steady_clock::time_point sent_at;
  std::thread sender([&] {
    for (int i = 0; i < 600; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      if (fs::exists(out / "solid" / "solid_000001.h5")) break;
    }
    sent_at = std::chrono::steady_clock::now();
    const pid_t pid = solid_rank_process(out, rank);
    ASSERT_GT(pid, 0) << "no process of solid rank " << rank;
    EXPECT_EQ(::kill(pid, signal), 0);
  });
  const int rc = cosim_run(scene_file("piston_2d"), out, "--solid-ranks 2 --set coupling.output.interval=0.01");
  const auto ended = std::chrono::steady_clock::now();
  sender.join();
  return {rc, std::chrono::duration<double>(ended - sent_at).count()};
}

// No process of the run in `out` is left.
void expect_nothing_left(const fs::path& out) {
  for (const char* p : {"fluid_solve[r]", "solid_solve[r]", "couple[r]"})
    EXPECT_NE(std::system(("pgrep -f '" + std::string(p) + " .*" + out.string() + "' > /dev/null").c_str()), 0)
        << p << " was left behind";
}

}  // namespace

// SIGSTOP of solid rank 0 of 2 in a coupled run (silent, not dead; the rank that holds the coupler's connection):
// rank 1's watchdog notices, the solid ends with code 5, the coupler stops the fluid, and run_summary.json names the
// solid and rank 0, all within 5 s of the stop (rank 0, resumed as the run ends, does not blame rank 1); no process
// of the run is left.
TEST(CoupledSolidRanks, AStoppedSolidRankEndsTheCoupledRunNamingTheRank) {
  const fs::path out = run_dir("solid_ranks_stopped");
  const auto [rc, after_stop] = signal_a_solid_rank(out, 0, SIGSTOP);
  EXPECT_NE(rc, 0) << run_logs(out);
  EXPECT_LT(after_stop, 5.0) << run_logs(out);
  const nlohmann::json s = nlohmann::json::parse(read_text(out / "run_summary.json"));
  EXPECT_EQ(s["status"].get<std::string>(), "failed") << s.dump(2);
  const nlohmann::json& f = s["failed_process"];
  EXPECT_EQ(f["name"].get<std::string>(), "solid") << s.dump(2);
  ASSERT_TRUE(f.contains("rank")) << s.dump(2);
  EXPECT_EQ(f["rank"].get<int>(), 0) << s.dump(2);
  EXPECT_EQ(f["noticed_by"].get<int>(), 1) << s.dump(2);
  EXPECT_EQ(f["ranks"].get<int>(), 2) << s.dump(2);
  EXPECT_NE(f["error"].get<std::string>().find("rank 0 of 2 has been silent"), std::string::npos) << s.dump(2);
  expect_nothing_left(out);
  std::printf("[ measured ] solid rank 0 of 2 stopped in a coupled run: the run ended %.2f s after the stop\n",
              after_stop);
}

// SIGKILL of solid rank 1 of 2: mpirun ends the other, the coupler stops the fluid, and run_summary.json names the
// solid and rank 1 (from mpirun's line in solid.log: no rank was left to write a summary) within 5 s.
TEST(CoupledSolidRanks, AKilledSolidRankEndsTheCoupledRunNamingTheRank) {
  const fs::path out = run_dir("solid_ranks_killed");
  const auto [rc, after_kill] = signal_a_solid_rank(out, 1, SIGKILL);
  EXPECT_NE(rc, 0) << run_logs(out);
  EXPECT_LT(after_kill, 5.0) << run_logs(out);
  const nlohmann::json s = nlohmann::json::parse(read_text(out / "run_summary.json"));
  EXPECT_EQ(s["status"].get<std::string>(), "failed") << s.dump(2);
  const nlohmann::json& f = s["failed_process"];
  EXPECT_EQ(f["name"].get<std::string>(), "solid") << s.dump(2);
  ASSERT_TRUE(f.contains("rank")) << s.dump(2);
  EXPECT_EQ(f["rank"].get<int>(), 1) << s.dump(2);
  EXPECT_NE(f["error"].get<std::string>().find("exited on signal 9"), std::string::npos) << s.dump(2);
  expect_nothing_left(out);
  std::printf("[ measured ] solid rank 1 of 2 killed in a coupled run: the run ended %.2f s after the kill\n",
              after_kill);
}
