// What another user of a shared node can see of a run: the token is on no command line and in no file of the run
// directory (cosim run passes it by the environment, readable by its owner alone), the coupler's ipc socket takes
// connections from its owner only, and a run directory too long for a socket name gets a private socket directory
// (named at random, not from the token) that goes with the run.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>

#include <chrono>
#include <thread>

#include "coupling_test_util.h"

using namespace cosim;
using namespace cosim::test;

namespace {

std::string environment_value(int pid, const std::string& key) {
  const std::string env = read_file(fs::path("/proc") / std::to_string(pid) / "environ");
  const std::string k = key + "=";
  for (std::size_t at = 0; at < env.size();) {
    const std::size_t end = env.find('\0', at);
    const std::string entry = env.substr(at, end == std::string::npos ? std::string::npos : end - at);
    if (entry.rfind(k, 0) == 0) return entry.substr(k.size());
    if (end == std::string::npos) break;
    at = end + 1;
  }
  return "";
}

std::string command_line(int pid) {
  std::string cmd = read_file(fs::path("/proc") / std::to_string(pid) / "cmdline");
  for (char& c : cmd)
    if (c == '\0') c = ' ';
  return cmd;
}

// Starts cosim run into `run` with scripted solvers that run until stopped; returns once the coupler is up.
launcher::Child start_run(const fs::path& dir, const fs::path& run, int& coupler_pid) {
  const fs::path scene = write_scene(dir, "  time: {end: 1.0e9}\n");
  launcher::Child c = child("cosim",
                            {bin("cosim").string(), "run", scene.string(), "--out", run.string(), "--quiet",
                             "--fluid-exe", bin("cosim_scripted_peer").string() + " --role fluid --dt 1e-4",
                             "--solid-exe", bin("cosim_scripted_peer").string() + " --role solid --dt 1e-4"},
                            dir);
  launcher::start(c);
  for (int i = 0; i < 500 && !(coupler_pid = pid_with_arguments({bin("coupler").string(), run.string()})); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // the peers connected
  return c;
}

}  // namespace

TEST(RunSecrets, TheTokenIsOnNoCommandLineAndTheSocketIsTheOwnersOnly) {
  const fs::path dir = test_dir("secrets");
  const fs::path run = dir / "run";
  int coupler = 0;
  launcher::Child cosim = start_run(dir, run, coupler);
  ASSERT_NE(coupler, 0) << read_file(cosim.log);
  const std::string token = environment_value(coupler, "COSIM_TOKEN");
  ASSERT_GE(token.size(), 16u) << command_line(coupler) << "\n" << read_file(cosim.log);
  for (const char* role : {"--role fluid", "--role solid"}) {
    const int pid = pid_with_arguments({bin("cosim_scripted_peer").string(), role});
    ASSERT_NE(pid, 0) << role;
    EXPECT_EQ(command_line(pid).find(token), std::string::npos) << command_line(pid);
  }
  EXPECT_EQ(command_line(coupler).find(token), std::string::npos) << command_line(coupler);
  for (const auto& e : fs::recursive_directory_iterator(run))
    if (e.is_regular_file()) { EXPECT_EQ(read_file(e.path()).find(token), std::string::npos) << e.path(); }
  struct stat st {};
  ASSERT_EQ(::stat((run / "coupler.sock").c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 077, 0u) << std::oct << st.st_mode;  // no group or other access
  ::kill(cosim.pid, SIGTERM);
  std::vector<launcher::Child> cs{cosim};
  wait_all(cs, 10);
  EXPECT_FALSE(process_with_argument(run.string()));
}

TEST(RunSecrets, ALongRunDirectoryGetsAPrivateSocketDirectoryThatGoesWithTheRun) {
  const fs::path dir = test_dir("secrets_long");
  const fs::path run = dir / std::string(120, 'r');
  int coupler = 0;
  launcher::Child cosim = start_run(dir, run, coupler);
  ASSERT_NE(coupler, 0) << read_file(cosim.log);
  const std::string token = environment_value(coupler, "COSIM_TOKEN");
  const std::string cmd = command_line(coupler);
  const std::size_t at = cmd.find("ipc:///tmp/cosim-");
  ASSERT_NE(at, std::string::npos) << cmd;
  const fs::path sock = cmd.substr(at + 6, cmd.find(' ', at) - at - 6);
  EXPECT_EQ(sock.string().find(token.substr(0, 8)), std::string::npos) << sock;
  struct stat st {};
  ASSERT_EQ(::stat(sock.parent_path().c_str(), &st), 0) << sock;
  EXPECT_EQ(st.st_mode & 077, 0u) << std::oct << st.st_mode;
  ::kill(cosim.pid, SIGTERM);
  std::vector<launcher::Child> cs{cosim};
  wait_all(cs, 10);
  EXPECT_FALSE(fs::exists(sock.parent_path())) << sock;
}
