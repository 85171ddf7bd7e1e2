#include "common/parallel/launch_env.h"

#include <algorithm>
#include <cstdlib>

namespace cosim::parallel {

namespace {
int positive_env(const char* name) {
  const char* v = std::getenv(name);
  const int n = v ? std::atoi(v) : 0;
  return n > 0 ? n : 0;
}
}  // namespace

LaunchShape launch_shape() {
  LaunchShape s;
  if (const int n = positive_env("OMPI_COMM_WORLD_SIZE")) {
    s.ranks = n;
    s.ranks_on_node = std::max(1, positive_env("OMPI_COMM_WORLD_LOCAL_SIZE"));
  } else if (const int m = positive_env("SLURM_NTASKS")) {
    s.ranks = m;
    s.ranks_on_node = std::max(1, positive_env("SLURM_NTASKS_PER_NODE"));
  }
  s.ranks_on_node = std::min(s.ranks_on_node, s.ranks);
  return s;
}

}  // namespace cosim::parallel
