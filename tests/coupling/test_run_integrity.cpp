// What `cosim run` leaves on disk and returns when a process of the run fails or is killed: the process whose
// failure started the chain is named and its exit code returned, whatever the order in which the launcher reaps
// them; an output that cannot be created is an I/O failure (4); a killed launcher leaves a failed
// run_summary.json naming it; a coupling: section without a solid is refused.
#include <gtest/gtest.h>
#include <signal.h>

#include <nlohmann/json.hpp>
#include <thread>

#include "coupling_test_util.h"

using namespace cosim;
using namespace cosim::test;
using launcher::Child;

namespace {

double elapsed_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// `cosim run` of the 2D piston, long (only the test ends it), in dir/run.
Child long_piston_run(const fs::path& dir) {
  const fs::path scene = fs::path(COSIM_SOURCE_DIR) / "configs" / "piston_2d.yaml";
  return child("cosim",
               {bin("cosim").string(), "run", scene.string(), "--out", (dir / "run").string(), "--set",
                "coupling.time.end=1e3", "--quiet"},
               dir);
}

// Waits until the run is coupling (its interface history has grown) while `c` runs.
::testing::AssertionResult coupling_started(Child& c, const fs::path& run) {
  const fs::path hist = run / "coupler" / "interface_history.csv";
  const auto t0 = std::chrono::steady_clock::now();
  while (!fs::exists(hist) || fs::file_size(hist) < 500) {
    launcher::poll(c);
    if (!c.running) return ::testing::AssertionFailure() << c.name << " ended:\n" << read_file(c.log);
    if (elapsed_since(t0) > 30) return ::testing::AssertionFailure() << "no coupled cycles within 30 s";
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return ::testing::AssertionSuccess();
}

void wait_exit(Child& c, double limit) {
  const auto t0 = std::chrono::steady_clock::now();
  while (c.running && elapsed_since(t0) < limit) {
    launcher::poll(c);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  if (c.running) {
    ADD_FAILURE() << c.name << " still running after " << limit << " s";
    launcher::stop(c, 1.0);
  }
}

nlohmann::json summary_of(const fs::path& run) { return nlohmann::json::parse(read_file(run / "run_summary.json")); }

}  // namespace

// kill -9 of a solver: the coupler sees its connection close and stops the run at once (exit 5), the other solver
// ends (5); the launcher may reap any of them first. Over several runs, each solver killed in turn, cosim returns
// 137 and run_summary.json names the killed solver (2 of 6 named the coupler when the first reaped was blamed).
TEST(RunIntegrity, AKilledSolverIsTheCauseWhateverTheOrderOfReaping) {
  for (int i = 0; i < 4; ++i) {
    const std::string victim = i % 2 == 0 ? "fluid" : "solid";
    const fs::path dir = test_dir("killed_solver_" + std::to_string(i));
    Child run = long_piston_run(dir);
    launcher::start(run);
    ASSERT_TRUE(coupling_started(run, dir / "run"));
    const int pid = pid_with_arguments({bin(victim + "_solver").string(), (dir / "run").string()});
    ASSERT_GT(pid, 0);
    ::kill(pid, SIGKILL);
    wait_exit(run, 15.0);
    EXPECT_EQ(run.exit_code, 137) << victim << ":\n" << read_file(run.log);
    const nlohmann::json j = summary_of(dir / "run");
    EXPECT_EQ(j["status"], "failed");
    EXPECT_EQ(j["failed_process"]["name"], victim) << j.dump(2);
    EXPECT_EQ(j["failed_process"]["exit"], "killed by signal 9 (SIGKILL)") << j.dump(2);
    EXPECT_NE(read_file(run.log).find(victim + " (" + bin(victim + "_solver").string()), std::string::npos)
        << read_file(run.log);
    EXPECT_FALSE(process_with_argument((dir / "run").string()));
  }
}

// The fluid fails numerically (the light piston under standard conditions makes the embedded polygon invalid):
// its exit code 3, not the coupler's consequential 5, is cosim's, and the fluid is named.
TEST(RunIntegrity, ASolversNumericalFailureIsTheRunsExitCode) {
  const fs::path dir = test_dir("fluid_numerical");
  const fs::path scene = fs::path(COSIM_SOURCE_DIR) / "configs" / "piston_light_2d.yaml";
  const auto [rc, out] = run_shell(dir, bin("cosim").string() + " run " + scene.string() + " --out " +
                                            (dir / "run").string() + " --quiet --set coupling.mode=standard");
  EXPECT_EQ(rc, 3) << out;
  EXPECT_NE(out.find("fluid (" + bin("fluid_solver").string()), std::string::npos) << out;
  const nlohmann::json j = summary_of(dir / "run");
  EXPECT_EQ(j["failed_process"]["name"], "fluid") << j.dump(2);
  EXPECT_EQ(j["failed_process"]["exit_code"], 3) << j.dump(2);
  EXPECT_NE(j["failed_process"]["last_log_lines"].dump().find("the solid's surface cannot bound the fluid"),
            std::string::npos)
      << j.dump(2);
  // The coupler names the fluid as the peer that stopped the run.
  const nlohmann::json c = nlohmann::json::parse(read_file(dir / "run" / "coupler" / "coupler_summary.json"));
  EXPECT_EQ(c["peer"], "fluid") << c.dump(2);
}

// An output that cannot be created (its path is a file) is an I/O failure, exit code 4, for cosim as for a solver.
TEST(RunIntegrity, AnOutputThatCannotBeCreatedIsAnIoFailure) {
  const fs::path dir = test_dir("out_is_a_file");
  const fs::path file = dir / "a_file";
  std::ofstream(file) << "not a directory\n";
  const fs::path sod = fs::path(COSIM_SOURCE_DIR) / "configs" / "sod.yaml";
  const fs::path piston = fs::path(COSIM_SOURCE_DIR) / "configs" / "piston_2d.yaml";
  for (const fs::path& out : {file, file / "sub"}) {
    const auto [rc, text] = run_shell(dir, bin("cosim").string() + " run " + piston.string() + " --out " +
                                               out.string() + " --quiet --set coupling.time.end=1e-3");
    EXPECT_EQ(rc, 4) << text;
    EXPECT_NE(text.find("cannot create the run directory"), std::string::npos) << text;
    const auto [frc, ftext] = run_shell(dir, bin("fluid_solver").string() + " " + sod.string() + " --out " +
                                                 out.string() + " --quiet --set fluid.time.end=1e-3");
    EXPECT_EQ(frc, 4) << ftext;
  }
  EXPECT_EQ(read_file(file), "not a directory\n");
}

// kill -9 of cosim itself: its processes die with it (their parent-death signal) and the watcher it left beside
// them marks run_summary.json failed, naming the launcher, within moments; nothing of the run is left running.
TEST(RunIntegrity, AKilledLauncherLeavesItsFailureInTheRunSummary) {
  const fs::path dir = test_dir("killed_launcher");
  Child run = long_piston_run(dir);
  launcher::start(run);
  ASSERT_TRUE(coupling_started(run, dir / "run"));
  EXPECT_EQ(summary_of(dir / "run")["status"], "running");
  EXPECT_EQ(summary_of(dir / "run")["launcher_pid"], run.pid);
  ::kill(run.pid, SIGKILL);
  wait_exit(run, 5.0);
  const auto t0 = std::chrono::steady_clock::now();
  nlohmann::json j;
  while (elapsed_since(t0) < 5.0) {
    j = summary_of(dir / "run");
    if (j["status"] != "running" && !process_with_argument((dir / "run").string())) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  std::printf("the summary said so %.2f s after the launcher was killed\n", elapsed_since(t0));
  EXPECT_EQ(j["status"], "failed") << j.dump(2);
  EXPECT_NE(j["reason"].get<std::string>().find("the launcher (cosim, pid " + std::to_string(run.pid) + ") died"),
            std::string::npos)
      << j.dump(2);
  EXPECT_FALSE(process_with_argument((dir / "run").string()));
  const nlohmann::json h = nlohmann::json::parse(read_file(dir / "run" / "run_history.json"));
  ASSERT_EQ(h["attempts"].size(), 1u);
  EXPECT_EQ(h["attempts"][0]["status"], "failed");
  // The directory is free again: a run into it starts (its lock went with the watcher).
  const fs::path scene = fs::path(COSIM_SOURCE_DIR) / "configs" / "piston_2d.yaml";
  const auto [rc, out] = run_shell(dir, bin("cosim").string() + " run " + scene.string() + " --out " +
                                            (dir / "run").string() + " --quiet --set coupling.time.end=1e-3");
  EXPECT_EQ(rc, 0) << out;
}

// A scene with a coupling: section and no solid: is refused, naming the file and the key, by cosim check, cosim
// run and fluid_solver alike (a fluid-only run would read half of coupling:, e.g. its end time but not its output).
TEST(RunIntegrity, ACouplingSectionWithoutASolidIsRefused) {
  const fs::path dir = test_dir("coupling_without_solid");
  const fs::path scene = dir / "no_solid.yaml";
  std::string text = read_file(fs::path(COSIM_SOURCE_DIR) / "configs" / "piston_light_2d.yaml");
  text = text.substr(0, text.find("\nsolid:") + 1);
  ASSERT_NE(text.find("\nfluid:"), std::string::npos);
  std::ofstream(scene) << text;
  const std::string expected = ": coupling: needs a solid: section (a coupled run)";
  for (const std::string& cmd :
       {bin("cosim").string() + " check " + scene.string(),
        bin("cosim").string() + " run " + scene.string() + " --out " + (dir / "run").string() + " --quiet",
        bin("fluid_solver").string() + " " + scene.string() + " --out " + (dir / "fluid").string() + " --quiet",
        bin("fluid_solver").string() + " " + scene.string() + " --check"}) {
    const auto [rc, out] = run_shell(dir, cmd);
    EXPECT_EQ(rc, 2) << cmd << "\n" << out;
    EXPECT_NE(out.find(expected), std::string::npos) << cmd << "\n" << out;
    EXPECT_NE(out.find(scene.string() + ":"), std::string::npos) << cmd << "\n" << out;
  }
  EXPECT_FALSE(fs::exists(dir / "run"));
  EXPECT_FALSE(fs::exists(dir / "fluid"));
}
