#include "common/app/version.h"

#include "cosim_version.h"

namespace cosim::app {

std::string version() { return COSIM_VERSION; }
std::string git_commit() { return COSIM_GIT_COMMIT; }
std::string version_line(const std::string& program) {
  return program + " " + version() + " (git " + git_commit() + ")";
}

}  // namespace cosim::app
