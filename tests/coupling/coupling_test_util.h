// Helpers of the coupling tests: scenes in a temporary directory, the three processes started with
// launcher/process.h, logs read back.
#pragma once

#include <sys/wait.h>

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "launcher/process.h"
#include "tests/support/scratch_dir.h"

namespace cosim::test {

namespace fs = std::filesystem;

inline fs::path bin(const std::string& exe) { return fs::path(COSIM_BINARY_DIR) / "bin" / exe; }
inline fs::path python_dir() { return fs::path(COSIM_BINARY_DIR) / "python"; }

// A fresh directory for one test.
inline fs::path test_dir(const std::string& name) {
  const fs::path d = cosim::test::scratch_path("coupling_" + name);
  fs::create_directories(d);
  return d;
}

inline std::string read_file(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

inline fs::path write_scene(const fs::path& dir, const std::string& coupling) {
  const fs::path p = dir / "scene.yaml";
  std::ofstream(p) << "name: test\nfluid: {dummy: 1}\nsolid: {dummy: 1}\ncoupling:\n" << coupling;
  return p;
}

inline launcher::Child child(const std::string& name, std::vector<std::string> argv, const fs::path& dir) {
  launcher::Child c;
  c.name = name;
  c.argv = std::move(argv);
  c.log = dir / (name + ".log");
  return c;
}

inline std::vector<std::string> peer_args(const std::string& role, const std::string& ep, const fs::path& scene,
                                          std::vector<std::string> extra = {}) {
  std::vector<std::string> a{bin("cosim_scripted_peer").string(),
                             "--role",
                             role,
                             "--endpoint",
                             ep,
                             "--token",
                             "tok",
                             "--scene",
                             scene.string(),
                             "--connect-timeout",
                             "3"};
  a.insert(a.end(), extra.begin(), extra.end());
  return a;
}

inline std::vector<std::string> coupler_args(const std::string& ep, const fs::path& scene, const fs::path& out,
                                             std::vector<std::string> extra = {}) {
  std::vector<std::string> a{
      bin("coupler").string(), scene.string(), "--endpoint", ep, "--token", "tok", "--out", out.string()};
  a.insert(a.end(), extra.begin(), extra.end());
  return a;
}

// Waits until every child exited or `seconds` passed; returns the seconds waited. Kills leftovers.
inline double wait_all(std::vector<launcher::Child>& cs, double seconds) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  for (;;) {
    bool any = false;
    for (auto& c : cs) {
      launcher::poll(c);
      any = any || c.running;
    }
    if (!any) return elapsed();
    if (elapsed() > seconds) {
      for (auto& c : cs) {
        EXPECT_FALSE(c.running) << c.describe() << " still running after " << seconds << " s";
        launcher::stop(c, 0.5);
      }
      return elapsed();
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

// The pid of a process (not this one) whose command line contains all of `texts`, 0 when none.
inline int pid_with_arguments(const std::vector<std::string>& texts) {
  for (const auto& e : fs::directory_iterator("/proc")) {
    const std::string name = e.path().filename();
    if (name.find_first_not_of("0123456789") != std::string::npos || std::to_string(::getpid()) == name) continue;
    std::string cmd = read_file(e.path() / "cmdline");
    for (char& c : cmd)
      if (c == '\0') c = ' ';
    bool all = !cmd.empty();
    for (const auto& t : texts) all = all && cmd.find(t) != std::string::npos;
    if (all) return std::stoi(name);
  }
  return 0;
}

// Exit code and output (stdout and stderr together) of a shell command, its output kept in dir/out.log.
inline std::pair<int, std::string> run_shell(const fs::path& dir, const std::string& cmd) {
  const fs::path log = dir / "out.log";
  const int rc = std::system((cmd + " > " + log.string() + " 2>&1").c_str());
  return {WIFEXITED(rc) ? WEXITSTATUS(rc) : -1, read_file(log)};
}

// True when some process's command line contains `text` (no process may be left running).
inline bool process_with_argument(const std::string& text) { return pid_with_arguments({text}) != 0; }

}  // namespace cosim::test
