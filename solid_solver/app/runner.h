// The standalone solid run: scene -> snapshots at the output times -> summary.json.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace cosim::solid {

struct RunOptions {
  std::string scene_file;
  std::filesystem::path out_dir;
  std::vector<std::string> overrides;
  bool quiet = false;
  int threads = 0;  // 0: scene value / OpenMP default
};

// Exit codes (as fluid_solver): 0 success, 2 bad input, 3 numerical failure, 4 I/O failure, 130 interrupted.
int run_solid(const RunOptions& opt);

}  // namespace cosim::solid
