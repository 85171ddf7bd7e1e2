#include "launcher/rank_launcher.h"

#include <unistd.h>

#include <cstdlib>
#include <thread>

namespace cosim::launcher {

std::vector<std::string> rank_launcher(int ranks) {
  if (ranks <= 1) return {};
  const std::string n = std::to_string(ranks);
  if (std::getenv("SLURM_JOB_ID")) return {"srun", "--ntasks", n, "--kill-on-bad-exit=1"};
  std::vector<std::string> words{"mpirun", "-np", n, "--bind-to", "none"};
  if (::geteuid() == 0) words.push_back("--allow-run-as-root");
  if (static_cast<unsigned>(ranks) > std::thread::hardware_concurrency()) words.push_back("--oversubscribe");
  return words;
}

}  // namespace cosim::launcher
