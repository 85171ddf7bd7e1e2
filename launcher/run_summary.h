// DIR/run_summary.json, written by `cosim run` at every end of a run: its status (completed, failed, interrupted),
// the process that failed (its exit code or signal and the last lines of its log), the coupled time and cycle
// reached, the wall time and every process's exit code. A failed run's cause is then in the run directory, not
// only on the launcher's terminal.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "launcher/process.h"

namespace cosim::launcher {

struct RunEnd {
  std::string status;             // completed | failed | interrupted
  std::string reason;             // one line: what ended the run
  const Child* failed = nullptr;  // the process that failed first, if one did
  double wall_seconds = 0;
};

// "exit code 5", "killed by signal 9 (SIGKILL)", "running".
std::string exit_description(const Child& c);

// Writes out/run_summary.json atomically (a failure to write is reported on stderr, never thrown).
void write_run_summary(const std::filesystem::path& out, const RunEnd& end, const std::vector<Child>& children,
                       bool coupled);

}  // namespace cosim::launcher
