// The program's version and the git commit it was built from, for --version and every summary.json.
#pragma once

#include <string>

namespace cosim::app {

std::string version();     // "0.9.0"
std::string git_commit();  // 12 hex digits, "-modified" when built from a changed tree, or "unknown"
std::string version_line(const std::string& program);  // "fluid_solver 0.9.0 (git 1a2b3c4d5e6f)"

}  // namespace cosim::app
