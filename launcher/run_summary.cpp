#include "launcher/run_summary.h"

#include <fmt/format.h>

#include <cctype>
#include <cstring>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "common/app/version.h"
#include "common/io/atomic_file.h"

namespace cosim::launcher {

std::string exit_description(const Child& c) {
  if (c.running) return "running";
  if (c.signal > 0) {
    const char* name = sigabbrev_np(c.signal);
    return fmt::format("killed by signal {}{}", c.signal, name ? fmt::format(" (SIG{})", name) : "");
  }
  return fmt::format("exit code {}", c.exit_code);
}

void write_run_summary(const std::filesystem::path& out, const RunEnd& end, const std::vector<Child>& children,
                       bool coupled) {
  try {
    nlohmann::json j;
    j["status"] = end.status;
    j["reason"] = end.reason;
    j["version"] = app::version();
    j["git_commit"] = app::git_commit();
    j["wall_seconds"] = end.wall_seconds;
    if (coupled) {
      // The last cycle the coupler completed: the last line of its interface history (cycle, time, ...); the end
      // time from its progress file (cycle, t, t_end, dt).
      std::ifstream hist(out / "coupler" / "interface_history.csv");
      std::string line, last;
      while (std::getline(hist, line))
        if (!line.empty() && std::isdigit(static_cast<unsigned char>(line[0]))) last = line;
      long cycle = 0;
      double t = 0, t_end = 0;
      char comma = 0;
      std::istringstream ls(last);
      if (ls >> cycle >> comma >> t) {
        j["cycle"] = cycle;
        j["time"] = t;
      }
      std::ifstream prog(out / "coupler" / "progress.txt");
      if (prog >> cycle >> t >> t_end) j["end_time"] = t_end;
    }
    nlohmann::json procs = nlohmann::json::array();
    for (const Child& c : children) {
      nlohmann::json p;
      p["name"] = c.name;
      p["program"] = c.argv.empty() ? "" : c.argv[0];
      p["pid"] = c.pid;
      p["exit"] = exit_description(c);
      p["exit_code"] = c.exit_code;
      p["log"] = c.log.filename().string();
      procs.push_back(p);
    }
    j["processes"] = procs;
    if (end.failed) {
      nlohmann::json f;
      f["name"] = end.failed->name;
      f["program"] = end.failed->argv.empty() ? "" : end.failed->argv[0];
      f["exit"] = exit_description(*end.failed);
      f["exit_code"] = end.failed->exit_code;
      std::istringstream lines(tail(end.failed->log, 15));
      nlohmann::json last = nlohmann::json::array();
      for (std::string l; std::getline(lines, l);) last.push_back(l);
      f["last_log_lines"] = last;
      j["failed_process"] = f;
    }
    io::write_file_atomically(out / "run_summary.json", j.dump(2) + "\n");
  } catch (const std::exception& e) {
    std::cerr << "cosim: cannot write " << (out / "run_summary.json").string() << ": " << e.what() << "\n";
  }
}

}  // namespace cosim::launcher
