// The real solvers and their coupler under signals: SIGTERM ends a solver waiting on a silent (SIGSTOPped) coupler
// at once, exit 130 and summary.json status "interrupted"; a killed coupler is seen at once (its connection closes),
// not after the heartbeat timeout, also by a fluid or a solid on 2 ranks (together, one summary); a stopped solver ends
// `cosim run` within 5 s with the cause in run_summary.json; one run per run directory.
#include <gtest/gtest.h>
#include <signal.h>

#include <nlohmann/json.hpp>
#include <thread>

#include "coupling_test_util.h"

using namespace cosim;
using namespace cosim::test;
using launcher::Child;

namespace {

double seconds_until_exit(Child& c, double limit) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  while (c.running && elapsed() < limit) {
    launcher::poll(c);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return elapsed();
}

// Waits until the run in `run_dir` is coupling (its interface history has grown) while all of `procs` run.
::testing::AssertionResult running_coupled(const std::vector<Child*>& procs, const fs::path& run_dir) {
  const fs::path hist = run_dir / "coupler" / "interface_history.csv";
  const auto t0 = std::chrono::steady_clock::now();
  while (!fs::exists(hist) || fs::file_size(hist) < 2000) {
    for (Child* c : procs) {
      launcher::poll(*c);
      if (!c->running) return ::testing::AssertionFailure() << c->name << " ended:\n" << read_file(c->log);
    }
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() > 30)
      return ::testing::AssertionFailure() << "no coupled cycles within 30 s";
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return ::testing::AssertionSuccess();
}

// Coupler, fluid_solver and solid_solver on the 2D piston, run long with a long heartbeat timeout (only what the
// test does can end them soon), started and running coupled (the interface history grows).
struct RealRun {
  fs::path dir;
  std::vector<Child> cs;  // coupler, fluid, solid
  // fluid_ranks, solid_ranks > 1: that solver under mpirun.
  explicit RealRun(const std::string& name, int fluid_ranks = 1, int solid_ranks = 1) {
    dir = test_dir(name);
    const fs::path scene = fs::path(COSIM_SOURCE_DIR) / "configs" / "piston_2d.yaml";
    const std::string ep = "ipc://" + (dir / "c.sock").string();
    const std::vector<std::string> sets{"--set", "coupling.time.end=1e3", "--set", "coupling.timeout=30"};
    auto with_sets = [&](std::vector<std::string> a) {
      a.insert(a.end(), sets.begin(), sets.end());
      return a;
    };
    const auto solver = [&](const std::string& program, const std::string& out, int ranks) {
      std::vector<std::string> argv;
      if (ranks > 1)
        argv = {"mpirun", "--allow-run-as-root", "--oversubscribe", "--bind-to", "none", "-np", std::to_string(ranks)};
      for (const std::string& a :
           {bin(program).string(), scene.string(), std::string("--out"), (dir / out).string(), std::string("--coupler"),
            ep, std::string("--token"), std::string("tok"), std::string("--quiet")})
        argv.push_back(a);
      return with_sets(argv);
    };
    cs = {child("coupler", with_sets(coupler_args(ep, scene, dir / "coupler")), dir),
          child("fluid", solver("fluid_solver", "fluid", fluid_ranks), dir),
          child("solid", solver("solid_solver", "solid", solid_ranks), dir)};
    for (auto& c : cs) launcher::start(c);
  }
  ::testing::AssertionResult running_coupled() { return ::running_coupled({&cs[0], &cs[1], &cs[2]}, dir); }
  // Kills the coupler outright; the seconds until every process has ended (at most 10).
  double seconds_to_end_after_the_coupler_is_killed() {
    ::kill(cs[0].pid, SIGKILL);
    const auto t0 = std::chrono::steady_clock::now();
    wait_all(cs, 10);
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  nlohmann::json summary(int i) const { return nlohmann::json::parse(read_file(dir / cs[i].name / "summary.json")); }
};

}  // namespace

TEST(SolverSignals, SigtermEndsASolverWaitingOnASilentCouplerAtOnceWithItsSummary) {
  RealRun r("sigterm");
  ASSERT_TRUE(r.running_coupled());
  auto& cs = r.cs;
  ::kill(cs[0].pid, SIGSTOP);  // the coupler goes silent, its socket stays open
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  for (int i : {1, 2}) {
    ::kill(cs[i].pid, SIGTERM);
    const double waited = seconds_until_exit(cs[i], 5.0);
    EXPECT_FALSE(cs[i].running) << cs[i].name;
    EXPECT_LT(waited, 1.0) << cs[i].name;
    EXPECT_EQ(cs[i].exit_code, 130) << cs[i].name << ":\n" << read_file(cs[i].log);
    ASSERT_TRUE(fs::exists(r.dir / cs[i].name / "summary.json")) << cs[i].name;
    const nlohmann::json j = r.summary(i);
    EXPECT_EQ(j["status"], "interrupted") << cs[i].name;
    std::printf("%s: exited %.2f s after SIGTERM, code %d, summary status %s\n", cs[i].name.c_str(), waited,
                cs[i].exit_code, j["status"].get<std::string>().c_str());
  }
  ::kill(cs[0].pid, SIGKILL);
  wait_all(cs, 5);
  EXPECT_FALSE(process_with_argument(r.dir.string()));
}

// A coupler killed outright: the solvers see its connection close and stop at once (exit 5, summary failed with
// the cause), not after their heartbeat timeout (30 s here).
TEST(SolverSignals, ASolverSeesItsCouplerDieAtOnce) {
  RealRun r("coupler_killed");
  ASSERT_TRUE(r.running_coupled());
  auto& cs = r.cs;
  const double waited = r.seconds_to_end_after_the_coupler_is_killed();
  std::printf("both solvers ended %.2f s after the coupler was killed\n", waited);
  EXPECT_LT(waited, 1.5);
  for (int i : {1, 2}) {
    EXPECT_EQ(cs[i].exit_code, 5) << cs[i].name << ":\n" << read_file(cs[i].log);
    ASSERT_TRUE(fs::exists(r.dir / cs[i].name / "summary.json")) << cs[i].name;
    const nlohmann::json j = r.summary(i);
    EXPECT_EQ(j["status"], "failed") << cs[i].name;
    EXPECT_NE(j.dump().find("closed the connection"), std::string::npos) << j.dump();
  }
  EXPECT_FALSE(process_with_argument(r.dir.string()));
}

// The same with the fluid on 2 MPI ranks: rank 0 sees the connection close and every rank receives the failure
// through it, so the ranks end together at once, with one summary (the cause, both ranks, none blamed).
TEST(SolverSignals, AFluidOnTwoRanksSeesItsCouplerDieTogether) {
  RealRun r("coupler_killed_ranks", 2);
  ASSERT_TRUE(r.running_coupled());
  auto& cs = r.cs;
  const double waited = r.seconds_to_end_after_the_coupler_is_killed();
  std::printf("the fluid's 2 ranks and the solid ended %.2f s after the coupler was killed\n", waited);
  EXPECT_LT(waited, 3.0);
  EXPECT_EQ(cs[1].exit_code, 5) << read_file(cs[1].log);
  const nlohmann::json j = r.summary(1);
  EXPECT_EQ(j["status"], "failed") << j.dump();
  EXPECT_NE(j.dump().find("closed the connection"), std::string::npos) << j.dump();
  EXPECT_EQ(j["parallel"]["ranks"].get<int>(), 2) << j.dump();
  EXPECT_FALSE(j["parallel"].contains("failed_rank")) << j.dump();
  EXPECT_FALSE(process_with_argument(r.dir.string()));
}

// The same with the solid on 2 MPI ranks (its rank 0 holds the connection).
TEST(SolverSignals, ASolidOnTwoRanksSeesItsCouplerDieTogether) {
  RealRun r("coupler_killed_solid_ranks", 1, 2);
  ASSERT_TRUE(r.running_coupled());
  auto& cs = r.cs;
  const double waited = r.seconds_to_end_after_the_coupler_is_killed();
  std::printf("the fluid and the solid's 2 ranks ended %.2f s after the coupler was killed\n", waited);
  EXPECT_LT(waited, 3.0);
  EXPECT_EQ(cs[2].exit_code, 5) << read_file(cs[2].log);
  const nlohmann::json j = r.summary(2);
  EXPECT_EQ(j["status"], "failed") << j.dump();
  EXPECT_NE(j.dump().find("closed the connection"), std::string::npos) << j.dump();
  EXPECT_EQ(j["parallel"]["ranks"].get<int>(), 2) << j.dump();
  EXPECT_FALSE(j["parallel"].contains("failed_rank")) << j.dump();
  EXPECT_FALSE(process_with_argument(r.dir.string()));
}

// `cosim run` with a solver stopped (SIGSTOP): the coupler declares it dead after its timeout (3 s), the launcher
// stops everything together (SIGTERM and SIGCONT, so the stopped solver too ends by its handler and writes its
// summary): the run ends within 5 s of the stop, with the cause on the launcher's output.
TEST(SolverSignals, AStoppedSolverEndsTheRunWithinFiveSeconds) {
  const fs::path dir = test_dir("stopped_solver");
  const fs::path scene = fs::path(COSIM_SOURCE_DIR) / "configs" / "piston_2d.yaml";
  Child run = child("cosim",
                    {bin("cosim").string(), "run", scene.string(), "--out", (dir / "run").string(), "--set",
                     "coupling.time.end=1e3", "--quiet"},
                    dir);
  launcher::start(run);
  ASSERT_TRUE(running_coupled({&run}, dir / "run"));
  const int fluid = pid_with_arguments({bin("fluid_solver").string(), (dir / "run").string()});
  ASSERT_GT(fluid, 0);
  ::kill(fluid, SIGSTOP);
  const double waited = seconds_until_exit(run, 15.0);
  std::printf("the run ended %.2f s after its fluid solver was stopped, exit code %d\n", waited, run.exit_code);
  EXPECT_LT(waited, 5.0);
  EXPECT_EQ(run.exit_code, 5) << read_file(run.log);
  EXPECT_NE(read_file(run.log).find("declared dead"), std::string::npos) << read_file(run.log);
  const fs::path summary = dir / "run" / "fluid" / "summary.json";
  ASSERT_TRUE(fs::exists(summary));
  EXPECT_EQ(nlohmann::json::parse(read_file(summary))["status"], "interrupted");
  // The cause is in the run directory: the coupler failed first, naming the stopped solver.
  const fs::path rs = dir / "run" / "run_summary.json";
  ASSERT_TRUE(fs::exists(rs));
  const nlohmann::json j = nlohmann::json::parse(read_file(rs));
  EXPECT_EQ(j["status"], "failed");
  EXPECT_EQ(j["failed_process"]["name"], "coupler");
  EXPECT_EQ(j["failed_process"]["exit"], "exit code 5");
  EXPECT_NE(j["failed_process"]["last_log_lines"].dump().find("declared dead"), std::string::npos) << j.dump(2);
  EXPECT_GT(j["cycle"].get<long>(), 0);
  EXPECT_GT(j["time"].get<double>(), 0.0);
  EXPECT_EQ(j["processes"].size(), 3u);
  if (run.running) launcher::stop(run, 1.0);
  EXPECT_FALSE(process_with_argument((dir / "run").string()));
}

// A second `cosim run` into the directory of a running one is refused at once (it would mix their snapshots and
// logs); the first runs on; once it has ended the directory can be used again.
TEST(RunDirectory, ASecondRunIntoARunningRunsDirectoryIsRefused) {
  const fs::path dir = test_dir("run_lock");
  const fs::path scene = fs::path(COSIM_SOURCE_DIR) / "configs" / "piston_2d.yaml";
  const auto cosim_run = [&](const std::string& name, const std::string& end) {
    return child(name,
                 {bin("cosim").string(), "run", scene.string(), "--out", (dir / "run").string(), "--set",
                  "coupling.time.end=" + end, "--quiet"},
                 dir);
  };
  Child first = cosim_run("first", "1e3");
  launcher::start(first);
  ASSERT_TRUE(running_coupled({&first}, dir / "run"));
  Child second = cosim_run("second", "1e-3");
  launcher::start(second);
  const double waited = seconds_until_exit(second, 10.0);
  EXPECT_LT(waited, 2.0);
  EXPECT_EQ(second.exit_code, 2);
  const std::string msg = read_file(second.log);
  EXPECT_NE(msg.find("the run directory is in use by another run (cosim pid " + std::to_string(first.pid) + ")"),
            std::string::npos)
      << msg;
  launcher::poll(first);
  EXPECT_TRUE(first.running);  // undisturbed
  launcher::stop(first, 5.0);
  EXPECT_EQ(first.exit_code, 130);
  Child third = cosim_run("third", "1e-3");  // the lock went with the first run
  launcher::start(third);
  seconds_until_exit(third, 60.0);
  EXPECT_EQ(third.exit_code, 0) << read_file(third.log);
}
