// The real solvers under a coupler that has gone silent (SIGSTOP): SIGTERM ends each of them at once, with exit
// code 130 and its summary.json written with status "interrupted", instead of at its heartbeat timeout.
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

}  // namespace

TEST(SolverSignals, SigtermEndsASolverWaitingOnASilentCouplerAtOnceWithItsSummary) {
  const fs::path dir = test_dir("sigterm");
  const fs::path scene = fs::path(COSIM_SOURCE_DIR) / "configs" / "piston_2d.yaml";
  const std::string ep = "ipc://" + (dir / "c.sock").string();
  // A long run with a long heartbeat timeout: only the signal can end the solvers' wait within the test.
  const std::vector<std::string> sets{"--set", "coupling.time.end=1e3", "--set", "coupling.timeout=30"};
  auto with_sets = [&](std::vector<std::string> a) {
    a.insert(a.end(), sets.begin(), sets.end());
    return a;
  };
  std::vector<Child> cs{
      child("coupler", with_sets(coupler_args(ep, scene, dir / "coupler")), dir),
      child("fluid", with_sets({bin("fluid_solver").string(), scene.string(), "--out", (dir / "fluid").string(),
                                "--coupler", ep, "--token", "tok", "--quiet"}),
            dir),
      child("solid", with_sets({bin("solid_solver").string(), scene.string(), "--out", (dir / "solid").string(),
                                "--coupler", ep, "--token", "tok", "--quiet"}),
            dir)};
  for (auto& c : cs) launcher::start(c);
  // Running coupled: the interface history grows.
  const auto t0 = std::chrono::steady_clock::now();
  while (!fs::exists(dir / "coupler" / "interface_history.csv") ||
         fs::file_size(dir / "coupler" / "interface_history.csv") < 2000) {
    for (auto& c : cs) launcher::poll(c);
    ASSERT_TRUE(cs[0].running && cs[1].running && cs[2].running) << read_file(cs[0].log) << read_file(cs[1].log);
    ASSERT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 30.0);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ::kill(cs[0].pid, SIGSTOP);  // the coupler goes silent, its socket stays open
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  for (int i : {1, 2}) {
    ::kill(cs[i].pid, SIGTERM);
    const double waited = seconds_until_exit(cs[i], 5.0);
    EXPECT_FALSE(cs[i].running) << cs[i].name;
    EXPECT_LT(waited, 1.0) << cs[i].name;
    EXPECT_EQ(cs[i].exit_code, 130) << cs[i].name << ":\n" << read_file(cs[i].log);
    const fs::path summary = dir / cs[i].name / "summary.json";
    ASSERT_TRUE(fs::exists(summary)) << cs[i].name;
    const nlohmann::json j = nlohmann::json::parse(read_file(summary));
    EXPECT_EQ(j["status"], "interrupted") << cs[i].name;
    std::printf("%s: exited %.2f s after SIGTERM, code %d, summary status %s\n", cs[i].name.c_str(), waited,
                cs[i].exit_code, j["status"].get<std::string>().c_str());
  }
  ::kill(cs[0].pid, SIGKILL);
  wait_all(cs, 5);
  EXPECT_FALSE(process_with_argument(dir.string()));
}
