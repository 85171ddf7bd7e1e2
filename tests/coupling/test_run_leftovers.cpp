// What a run that does not complete leaves behind: a run that cannot start leaves no run directory, a failed run
// keeps its logs and run_summary.json but no empty output folders, and no ipc socket file stays, neither in the
// run directory nor where a coupler started by hand bound it.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include "coupling_test_util.h"

using namespace cosim;
using namespace cosim::test;

namespace {

int run_command(const std::string& cmd, const fs::path& log) {
  const int rc = std::system((cmd + " > " + log.string() + " 2>&1").c_str());
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

TEST(RunLeftovers, ARunThatCannotStartLeavesNoRunDirectory) {
  const fs::path dir = test_dir("leftover_nostart");
  const fs::path scene = write_scene(dir, "  time: {end: 1.0}\n");
  const fs::path run = dir / "run";
  // (scripted solvers: the scene's fluid and solid sections are placeholders the real solvers' checks refuse)
  const std::string peers = " --fluid-exe '" + bin("cosim_scripted_peer").string() + " --role fluid' --solid-exe '" +
                            bin("cosim_scripted_peer").string() + " --role solid'";
  const int rc = run_command(
      bin("cosim").string() + " run " + scene.string() + " --out " + run.string() + " --tcp not-an-address" + peers,
      dir / "cosim.log");
  EXPECT_EQ(rc, 2);
  EXPECT_NE(read_file(dir / "cosim.log").find("--tcp not-an-address: not an IPv4 address"), std::string::npos)
      << read_file(dir / "cosim.log");
  EXPECT_FALSE(fs::exists(run)) << "a run that never started left " << run;
}

TEST(RunLeftovers, AFailedRunKeepsItsSummaryButNoEmptyFolderAndNoSocket) {
  const fs::path dir = test_dir("leftover_failed");
  // a fluid that makes its output folder and waits (stopped before it writes anything), a solid that fails
  const fs::path fluid = dir / "wait.sh", solid = dir / "fail.sh";
  std::ofstream(fluid) << "#!/bin/sh\nmkdir -p \"$3\"\nexec sleep 30\n";  // $3: the DIR of --out DIR
  std::ofstream(solid) << "#!/bin/sh\nsleep 0.5\necho 'solid gives up' >&2\nexit 3\n";
  for (const fs::path& p : {fluid, solid}) fs::permissions(p, fs::perms::owner_all);
  const fs::path run = dir / "run";
  const int rc = run_command(
      bin("cosim").string() + " run " + (fs::path(COSIM_SOURCE_DIR) / "configs" / "piston_1d.yaml").string() +
          " --out " + run.string() + " --quiet --fluid-exe " + fluid.string() + " --solid-exe " + solid.string(),
      dir / "cosim.log");
  EXPECT_EQ(rc, 3) << read_file(dir / "cosim.log");
  const std::string summary = read_file(run / "run_summary.json");
  EXPECT_NE(summary.find("\"status\": \"failed\""), std::string::npos) << summary;
  EXPECT_NE(summary.find("solid gives up"), std::string::npos) << summary;
  for (const auto& e : fs::directory_iterator(run))
    if (e.is_directory()) { EXPECT_FALSE(fs::is_empty(e.path())) << e.path() << " is an empty folder"; }
  EXPECT_FALSE(fs::exists(run / "fluid"));
  EXPECT_FALSE(fs::exists(run / "coupler.sock"));
  EXPECT_FALSE(process_with_argument(run.string()));
}

TEST(RunLeftovers, ACouplerRemovesTheSocketFileItBound) {
  const fs::path dir = test_dir("leftover_socket");
  const fs::path scene = write_scene(dir, "  time: {end: 1.0}\n  connect_timeout: 0.3\n");
  const fs::path sock = dir / "c.sock";
  const int rc = run_command(bin("coupler").string() + " " + scene.string() + " --endpoint ipc://" + sock.string() +
                                 " --out " + (dir / "out").string(),
                             dir / "coupler.log");
  EXPECT_NE(rc, 0);  // nobody connected
  EXPECT_NE(read_file(dir / "coupler.log").find("listening on ipc://" + sock.string()), std::string::npos)
      << read_file(dir / "coupler.log");
  EXPECT_FALSE(fs::exists(fs::symlink_status(sock))) << sock << " is left behind";
}

}  // namespace
