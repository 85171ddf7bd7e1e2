#include "launcher/run_summary.h"

#include <fmt/format.h>
#include <unistd.h>

#include <cctype>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "common/app/version.h"
#include "common/io/atomic_file.h"

namespace cosim::launcher {

namespace {
nlohmann::json read_json(const std::filesystem::path& p) {
  std::ifstream in(p);
  if (!in) return nullptr;
  try {
    return nlohmann::json::parse(in);
  } catch (const std::exception&) { return nullptr; }
}

// A rank that mpirun saw end on a signal (killed, crashed), from its line in the solver's log ("mpirun noticed that
// process rank 1 with PID 4242 on node n1 exited on signal 9 (Killed)."): the rank and that line, or rank -1.
std::pair<int, std::string> rank_ended_by_signal(const std::filesystem::path& log) {
  std::istringstream lines(tail(log, 40));
  const std::string mark = "mpirun noticed that process rank ";
  for (std::string l; std::getline(lines, l);) {
    const std::size_t at = l.find(mark);
    if (at == std::string::npos || l.find("exited on signal", at) == std::string::npos) continue;
    int rank = -1;
    if (std::sscanf(l.c_str() + at + mark.size(), "%d", &rank) != 1) continue;
    std::string what = l.substr(at);
    while (!what.empty() && (what.back() == ' ' || what.back() == '.')) what.pop_back();
    return {rank, what};
  }
  return {-1, ""};
}

// The attempts of run_history.json; a run directory written before it existed: its run_summary.json as attempt 1.
nlohmann::json read_attempts(const std::filesystem::path& out) {
  const nlohmann::json h = read_json(out / "run_history.json");
  if (h.is_object() && h.contains("attempts") && h["attempts"].is_array()) return h["attempts"];
  nlohmann::json list = nlohmann::json::array();
  const nlohmann::json s = read_json(out / "run_summary.json");
  if (s.is_object() && s.contains("status"))
    list.push_back({{"attempt", 1}, {"kind", "run"}, {"status", s["status"]}, {"reason", s.value("reason", "")}});
  return list;
}

// The attempt's entry replaced (same number) or added.
void record_attempt(const std::filesystem::path& out, const nlohmann::json& entry, bool fresh) {
  nlohmann::json list = fresh ? nlohmann::json::array() : read_attempts(out);
  bool found = false;
  for (auto& a : list)
    if (a.value("attempt", 0) == entry["attempt"].get<int>()) {
      a = entry;
      found = true;
    }
  if (!found) list.push_back(entry);
  io::write_file_atomically(out / "run_history.json", nlohmann::json{{"attempts", list}}.dump(2) + "\n");
}

nlohmann::json attempt_entry(const nlohmann::json& summary) {
  nlohmann::json e = {{"attempt", summary.value("attempt", 1)},
                      {"kind", summary.value("kind", "run")},
                      {"status", summary.value("status", "")},
                      {"reason", summary.value("reason", "")},
                      {"started", summary.value("started", "")},
                      {"ended", summary.value("ended", "")},
                      {"launcher_pid", summary.value("launcher_pid", 0L)}};
  if (summary.contains("restart_set")) e["restart_set"] = summary["restart_set"];
  if (summary.contains("failed_process")) e["failed_process"] = summary["failed_process"].value("name", "");
  return e;
}
}  // namespace

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  ::gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

Attempt next_attempt(const std::filesystem::path& out, bool restart, const std::string& restart_set) {
  Attempt a;
  a.restart = restart;
  a.restart_set = restart_set;
  a.started = utc_now();
  a.launcher_pid = ::getpid();
  if (restart) {
    int last = 0;
    for (const auto& e : read_attempts(out)) last = std::max(last, e.value("attempt", 0));
    a.number = last + 1;
  }
  return a;
}

long running_launcher(const std::filesystem::path& out) {
  const nlohmann::json j = read_json(out / "run_summary.json");
  if (!j.is_object() || j.value("status", "") != "running") return 0;
  return std::max(1L, j.value("launcher_pid", 1L));
}

bool mark_launcher_died(const std::filesystem::path& out, long launcher_pid, const std::string& why) {
  try {
    nlohmann::json j = read_json(out / "run_summary.json");
    if (!j.is_object() || j.value("status", "") != "running") return false;
    if (launcher_pid != 0 && j.value("launcher_pid", 0L) != launcher_pid) return false;
    j["status"] = "failed";
    j["reason"] = why;
    j["ended"] = utc_now();
    if (j.contains("processes"))
      for (auto& p : j["processes"])
        if (p.value("exit", "") == "running") p["exit"] = "killed with the launcher";
    io::write_file_atomically(out / "run_summary.json", j.dump(2) + "\n");
    record_attempt(out, attempt_entry(j), false);
    return true;
  } catch (const std::exception&) { return false; }
}

std::string exit_description(const Child& c) {
  if (c.running) return "running";
  if (c.signal > 0) {
    const char* name = sigabbrev_np(c.signal);
    return fmt::format("killed by signal {}{}", c.signal, name ? fmt::format(" (SIG{})", name) : "");
  }
  return fmt::format("exit code {}", c.exit_code);
}

void write_run_summary(const std::filesystem::path& out, const RunEnd& end, const std::vector<Child>& children,
                       bool coupled, const Attempt& attempt) {
  try {
    nlohmann::json j;
    j["status"] = end.status;
    j["reason"] = end.reason;
    j["attempt"] = attempt.number;
    j["kind"] = attempt.restart ? "restart" : "run";
    if (attempt.restart) j["restart_set"] = attempt.restart_set;
    j["launcher_pid"] = attempt.launcher_pid;
    j["started"] = attempt.started;
    if (end.status != "running") j["ended"] = utc_now();
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
      if (c.name != "coupler") p["ranks"] = c.ranks;  // as launched (coupler_summary.json: as its Hello says)
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
      // A solver on several ranks names the rank that failed, or fell silent, in its summary.json.
      const nlohmann::json own = read_json(out / end.failed->name / "summary.json");
      if (own.is_object() && own.contains("parallel") && own["parallel"].contains("failed_rank")) {
        f["rank"] = own["parallel"]["failed_rank"];
        f["ranks"] = own["parallel"].value("ranks", 0);
        if (own["parallel"].contains("noticed_by")) f["noticed_by"] = own["parallel"]["noticed_by"];
        f["error"] = own.value("error", "");
      } else if (const auto [rank, line] = rank_ended_by_signal(end.failed->log); rank >= 0) {
        f["rank"] = rank;  // no rank was left to write a summary
        f["error"] = line;
      }
      j["failed_process"] = f;
    }
    io::write_file_atomically(out / "run_summary.json", j.dump(2) + "\n");
    record_attempt(out, attempt_entry(j), !attempt.restart);
  } catch (const std::exception& e) {
    std::cerr << "cosim: cannot write " << (out / "run_summary.json").string() << ": " << e.what() << "\n";
  }
}

}  // namespace cosim::launcher
