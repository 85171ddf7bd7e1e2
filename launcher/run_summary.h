// DIR/run_summary.json, written by `cosim run` when the processes start (status "running", the launcher's pid) and
// at every end of a run: its status (completed, failed, interrupted), the process that failed (its exit code or
// signal and the last lines of its log), the coupled time and cycle reached, the wall time and every process's exit
// code. A failed run's cause is then in the run directory, not only on the launcher's terminal.
// DIR/run_history.json: every attempt of the run (the run, then each restart): number, kind, status, reason,
// start and end (UTC), the checkpoint set a restart resumed from. A fresh run starts it again.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "launcher/process.h"

namespace cosim::launcher {

// One attempt of a run: the run itself or a restart of it.
struct Attempt {
  int number = 1;
  bool restart = false;
  std::string restart_set;  // the checkpoint set a restart resumed from
  std::string started;      // UTC, ISO 8601
  long launcher_pid = 0;
};

// The next attempt in out: 1 for a fresh run; for a restart one more than run_history.json (or an earlier
// run_summary.json without it) holds.
Attempt next_attempt(const std::filesystem::path& out, bool restart, const std::string& restart_set);
// "2024-05-01T12:00:00Z"
std::string utc_now();

struct RunEnd {
  std::string status;             // running | completed | failed | interrupted
  std::string reason;             // one line: what ended the run
  const Child* failed = nullptr;  // the process that failed first, if one did
  double wall_seconds = 0;
};

// "exit code 5", "killed by signal 9 (SIGKILL)", "running".
std::string exit_description(const Child& c);

// Writes out/run_summary.json atomically and records the attempt in out/run_history.json (a failure to write is
// reported on stderr, never thrown).
void write_run_summary(const std::filesystem::path& out, const RunEnd& end, const std::vector<Child>& children,
                       bool coupled, const Attempt& attempt);
// The launcher pid of run_summary.json when its status is "running", else 0.
long running_launcher(const std::filesystem::path& out);
// A summary left "running" (of launcher_pid, or of any launcher when launcher_pid is 0) becomes "failed" with
// `why` as its reason, in run_summary.json and run_history.json. True when it changed one.
bool mark_launcher_died(const std::filesystem::path& out, long launcher_pid, const std::string& why);

}  // namespace cosim::launcher
