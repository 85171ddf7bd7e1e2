// Runs of fluid_solver and solid_solver on several ranks (mpirun, oversubscribed on this machine's cores) and the
// comparison of two runs' snapshot series, bit for bit.
#pragma once

#include <sys/wait.h>

#include <gtest/gtest.h>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "common/io/hdf5_file.h"
#include "tests/support/scratch_dir.h"

namespace cosim::test {

struct RankRun {
  int code = -1;
  std::string log;  // stdout and stderr
  double seconds = 0;
};

inline std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p);
  return {std::istreambuf_iterator<char>(in), {}};
}

inline std::string scene_path(const std::string& name) {
  return std::string(COSIM_SOURCE_DIR) + "/configs/" + name + ".yaml";
}

// A scene file in the scratch directory, for scenes written by a test.
inline std::string write_scene(const std::string& name, const std::string& text) {
  const std::filesystem::path dir = scratch_path(name + "_scene");
  std::filesystem::create_directories(dir);
  std::ofstream(dir / (name + ".yaml")) << text;
  return (dir / (name + ".yaml")).string();
}

// The mpirun prefix for `ranks` ranks (no prefix for one: the solver started alone, as a user would).
inline std::string launcher(int ranks) {
  if (ranks <= 1) return "";
  return "mpirun --allow-run-as-root --oversubscribe --bind-to none -np " + std::to_string(ranks) + " ";
}

// Runs the shell command `cmd` (its output into `log`), killed after `limit_s` seconds: exit code, seconds, log.
inline RankRun run_timed(const std::string& cmd, const std::filesystem::path& log, int limit_s) {
  const auto t0 = std::chrono::steady_clock::now();
  const int status =
      std::system(("timeout -s KILL " + std::to_string(limit_s) + " " + cmd + " > " + log.string() + " 2>&1").c_str());
  RankRun r;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.log = read_text(log);
  return r;
}

// SOLVER (fluid_solver, solid_solver) SCENE --out OUT on `ranks` ranks, one thread each, at most `limit_s` seconds.
inline RankRun run_solver_ranks(const std::string& solver, int ranks, const std::string& scene,
                                const std::filesystem::path& out, const std::string& extra, int limit_s) {
  const std::filesystem::path log = out.string() + ".log";
  std::filesystem::create_directories(out.parent_path());
  return run_timed(launcher(ranks) + std::string(COSIM_BINARY_DIR) + "/bin/" + solver + " " + scene + " --out " +
                       out.string() + " --quiet --threads 1 " + extra,
                   log, limit_s);
}

inline RankRun run_fluid_ranks(int ranks, const std::string& scene, const std::filesystem::path& out,
                               const std::string& extra = "", int limit_s = 300) {
  return run_solver_ranks("fluid_solver", ranks, scene, out, extra, limit_s);
}

inline RankRun run_solid_ranks(int ranks, const std::string& scene, const std::filesystem::path& out,
                               const std::string& extra = "", int limit_s = 300) {
  return run_solver_ranks("solid_solver", ranks, scene, out, extra, limit_s);
}

inline nlohmann::json summary_of(const std::filesystem::path& out) {
  return nlohmann::json::parse(read_text(out / "summary.json"));
}

// The snapshot files of a run (prefix: "fluid_" or "solid_"), in order.
inline std::vector<std::filesystem::path> snapshots_of(const std::filesystem::path& out,
                                                       const std::string& prefix = "fluid_") {
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(out)) {
    const std::string name = e.path().filename().string();
    if (name.rfind(prefix, 0) == 0 && e.path().extension() == ".h5") files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

// "" when the two series have the same files, times, fields and values bit for bit; else the first difference.
inline std::string series_difference(const std::filesystem::path& a, const std::filesystem::path& b,
                                     const std::string& prefix = "fluid_") {
  const auto fa = snapshots_of(a, prefix), fb = snapshots_of(b, prefix);
  if (fa.empty()) return "no snapshots in " + a.string();
  if (fa.size() != fb.size())
    return std::to_string(fa.size()) + " snapshots in " + a.string() + ", " + std::to_string(fb.size()) + " in " +
           b.string();
  for (std::size_t i = 0; i < fa.size(); ++i) {
    const io::Hdf5File x(fa[i], io::Hdf5File::Mode::ReadOnly), y(fb[i], io::Hdf5File::Mode::ReadOnly);
    if (x.read_double_attribute("/", "time") != y.read_double_attribute("/", "time"))
      return fa[i].filename().string() + ": another time";
    if (x.dataset_names() != y.dataset_names()) return fa[i].filename().string() + ": other fields";
    for (const std::string& name : x.dataset_names()) {
      const std::vector<double> u = x.read_doubles(name), v = y.read_doubles(name);
      if (u.size() != v.size()) return fa[i].filename().string() + name + ": another size";
      for (std::size_t c = 0; c < u.size(); ++c)
        if (std::memcmp(&u[c], &v[c], sizeof(double)) != 0)
          return fa[i].filename().string() + name + "[" + std::to_string(c) + "]: " + std::to_string(u[c]) + " vs " +
                 std::to_string(v[c]);
    }
  }
  return "";
}

// The newest checkpoint set under run/checkpoints; empty when there is none.
inline std::filesystem::path newest_set(const std::filesystem::path& run) {
  std::filesystem::path newest;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(run / "checkpoints", ec))
    if (e.is_directory() && e.path() > newest) newest = e.path();
  return newest;
}

// SOLVER SCENE with `sets` on `from` ranks, stopped early by `stop_early` (arguments that end it after a set was
// written), then restarted from its newest set on `to` ranks with `sets`: the run's folder, its ends logged as
// failures of the calling test where they fail (then the folder is empty).
inline std::filesystem::path run_then_restart(const std::string& solver, const std::string& scene,
                                              const std::string& sets, const std::string& stop_early, int from, int to,
                                              const std::string& name) {
  const auto out = scratch_path(name);
  const RankRun a = run_solver_ranks(solver, from, scene, out, sets + " " + stop_early, 300);
  if (a.code != 0) {
    ADD_FAILURE() << name << ": the first run failed\n" << a.log;
    return {};
  }
  const std::filesystem::path set = newest_set(out);
  if (set.empty()) {
    ADD_FAILURE() << name << ": no checkpoint set\n" << a.log;
    return {};
  }
  const RankRun b = run_solver_ranks(solver, to, scene, out, sets + " --restart " + set.string(), 300);
  if (b.code != 0) {
    ADD_FAILURE() << name << ": the restart failed\n" << b.log;
    return {};
  }
  return out;
}

// A run of 2 ranks one of which was stopped (SIGSTOP): ended by the other's watchdog with code 5, the silent rank
// and the one that noticed it in summary.json and the log, no process of SOLVER left behind.
inline void expect_stopped_rank_named(const std::string& solver, const std::filesystem::path& out, const RankRun& r) {
  EXPECT_EQ(r.code, 5) << r.log;
  EXPECT_NE(r.log.find("has been silent for"), std::string::npos) << r.log;
  const nlohmann::json s = summary_of(out);
  EXPECT_EQ(s["status"].get<std::string>(), "failed");
  const int silent = s["parallel"]["failed_rank"].get<int>();
  EXPECT_TRUE(silent == 0 || silent == 1) << s.dump();
  EXPECT_EQ(s["parallel"]["noticed_by"].get<int>(), 1 - silent) << s.dump();
  EXPECT_NE(r.log.find("rank " + std::to_string(silent) + " of 2 has been silent"), std::string::npos) << r.log;
  const std::string pattern = solver.substr(0, solver.size() - 1) + "[" + solver.back() + "]";
  EXPECT_NE(std::system(("pgrep -f '" + pattern + " .*--out " + out.string() + " ' > /dev/null").c_str()), 0)
      << "a rank was left behind";
}

}  // namespace cosim::test
