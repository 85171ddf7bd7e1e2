// The launcher's watcher: a process beside `cosim run` that outlives it, so that a launcher killed with kill -9
// still leaves the fact on disk (run_summary.json marked failed, naming it) and no process of its run behind.
#pragma once

#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>

namespace cosim::launcher {

// A process beside the launcher that outlives it. When the launcher dies without ending the run (kill -9, a
// crash), the pipe from it closes: the watcher kills the process groups of the run's processes (they die of their
// parent-death signal; what they started dies this way), marks run_summary.json failed naming the launcher, and
// exits, holding the run directory's lock until then. At a normal end the launcher says so and reaps it.
struct Watcher {
  pid_t pid = -1;
  int fd = -1;  // the launcher's end of the pipe
  void tell(const std::string& line) const {
    if (fd >= 0) [[maybe_unused]]
      auto w = ::write(fd, line.data(), line.size());
  }
  void started(pid_t group) const { tell(fmt::format("P{}\n", group)); }
  Watcher() = default;
  Watcher(const Watcher&) = delete;
  Watcher& operator=(const Watcher&) = delete;
  ~Watcher() {
    if (pid <= 0) return;
    tell("D\n");
    ::close(fd);
    int status = 0;
    ::waitpid(pid, &status, 0);
  }
};

// Forks the watcher of the run in `out`; `leftovers` are files it removes if the launcher dies (the sockets). Without
// a pipe or a fork the run goes on unwatched.
void start_watcher(Watcher& w, const std::filesystem::path& out, const std::vector<std::filesystem::path>& leftovers);

}  // namespace cosim::launcher
