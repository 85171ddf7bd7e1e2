// `cosim run`: one scene, three processes (or the fluid alone when the scene has no solid: section, the solid alone
// when it has no fluid: section).
// Run directory layout: scene.yaml (the copy every process reads), launch.json (commands and endpoint),
// coupler.log / fluid.log / solid.log, and the processes' outputs in coupler/, fluid/, solid/, run_summary.json and
// view.py (the run's ParaView state, run_view.h).
// A run that cannot start leaves no directory it made; one that fails keeps no empty output folder.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace cosim::launcher {

struct LaunchOptions {
  std::string scene;
  std::filesystem::path out;           // run directory (default runs/<scene name>)
  std::vector<std::string> overrides;  // --set
  bool tcp = false;
  std::string tcp_host = "127.0.0.1";
  std::string fluid_cmd, solid_cmd, coupler_cmd;  // empty: <dir of cosim>/fluid_solver etc.; split on spaces
  std::filesystem::path bin_dir;                  // where the default executables are
  bool quiet = false;
  double progress_every = 30;     // [s] between progress lines when stderr is not a terminal
  std::filesystem::path restart;  // --restart RUN: resume the run in RUN from its newest complete checkpoint set
  long restart_from = -1;         // --from N: from set N instead (-1: the newest)
  int fluid_ranks = 0;            // --fluid-ranks N (0: the scene's launcher.fluid_ranks, else 1)
  int solid_ranks = 0;            // --solid-ranks N (0: the scene's launcher.solid_ranks, else 1)
};

// Runs to completion; returns 0, or the exit code of the process whose failure started the chain (docs/output.md,
// "Exit codes and blame"), 2 for bad input, 4 for an output that cannot be created, 130 when interrupted.
// Messages go to stderr.
int run(const LaunchOptions& opt);
// cosim check: the scene read and checked as run() does before it starts anything; 0 when valid, else 2.
int check(const LaunchOptions& opt);

// ipc://<dir>/coupler.sock, or ipc:///tmp/cosim-XXXXXX/coupler.sock (a private directory made for it) when that
// path is too long for a socket name.
std::string ipc_endpoint(const std::filesystem::path& dir);
// tcp://host:port with a port that was free a moment ago.
std::string tcp_endpoint(const std::string& host);
// 32 random hex digits.
std::string make_token();
// Splits a command line into words as a POSIX shell does for plain words: blanks separate them, '...' is literal,
// "..." keeps blanks (\" and \\ escaped), a backslash escapes the next character; no expansion. Throws
// std::runtime_error on an unclosed quote.
std::vector<std::string> split_command(const std::string& cmd);

}  // namespace cosim::launcher
