#include "common/app/threads.h"

#include <omp.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>

namespace cosim::app {

void prefer_passive_waiting(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY") != nullptr) return;
  if (::setenv("OMP_WAIT_POLICY", "PASSIVE", 0) != 0) return;
  ::execv("/proc/self/exe", argv);  // returns only on failure: run on with the runtime's default
}

int threads_for(long work, long min_work_per_thread) {
  static const int offered = omp_get_max_threads();  // before any omp_set_num_threads of ours
  const long n = min_work_per_thread > 0 ? work / min_work_per_thread : offered;
  return static_cast<int>(std::clamp<long>(n, 1, offered));
}

}  // namespace cosim::app
