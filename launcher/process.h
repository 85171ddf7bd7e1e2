// Child processes of the launcher: started in their own process group with stdout and stderr in a log file,
// killed with SIGKILL when the launcher dies (PR_SET_PDEATHSIG), so that no process is ever left running.
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace cosim::launcher {

struct Child {
  std::string name;               // "fluid", "solid", "coupler"
  std::vector<std::string> argv;  // argv[0]: the executable (searched in PATH when it has no '/')
  std::filesystem::path log;
  bool append_log = false;   // a restart adds to the log of the earlier attempts (else it starts empty)
  std::string log_header{};  // a line written to the log before the process starts ("" none)
  pid_t pid = -1;
  bool running = false;
  int exit_code = 0;             // 128 + signal when killed by a signal
  int signal = 0;                // the signal that killed it, 0 when it exited
  std::string describe() const;  // "fluid (build/bin/fluid_solver, pid 123)"
  int ranks = 1;                 // MPI ranks it was started on (mpirun -np N); 1 for a plain process
};

// Starts c (throws std::runtime_error naming the executable when fork/exec setup fails; a failing exec makes
// the child exit 127 with a message in its log).
void start(Child& c);
// Non-blocking: updates running/exit_code; true when the child has just exited.
bool poll(Child& c);
// SIGTERM (and SIGCONT, so that a stopped process handles it and writes its summary), up to grace seconds for it
// to exit, then SIGKILL; waits for it.
void stop(Child& c, double grace);
// The same for all running children at once, with one deadline.
void stop_all(std::vector<Child>& cs, double grace);

// The last n lines of a file ("" when unreadable).
std::string tail(const std::filesystem::path& file, int n);

}  // namespace cosim::launcher
