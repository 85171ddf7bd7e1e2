// Helpers of the coupled-scene tests: `cosim run` of a scene from configs/ into a temporary run directory,
// the coupler's interface history read back, and reference piston trajectories.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/scratch_dir.h"

namespace cosim::test {

namespace fs = std::filesystem;

inline fs::path bin(const std::string& exe) { return fs::path(COSIM_BINARY_DIR) / "bin" / exe; }
inline fs::path scene_file(const std::string& name) {
  return fs::path(COSIM_SOURCE_DIR) / "configs" / (name + ".yaml");
}

inline std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

inline fs::path run_dir(const std::string& name) { return cosim::test::scratch_path("coupled_" + name); }

// `cosim run SCENE --out DIR --quiet ARGS`; returns the exit code (stdout and stderr in DIR.log).
inline int cosim_run(const fs::path& scene, const fs::path& dir, const std::string& args = "") {
  const std::string cmd = bin("cosim").string() + " run " + scene.string() + " --out " + dir.string() + " --quiet " +
                          args + " > " + dir.string() + ".log 2>&1";
  const int rc = std::system(cmd.c_str());
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

// Everything a failed run left: the launcher's output and the three logs.
inline std::string run_logs(const fs::path& dir) {
  std::string s = read_text(fs::path(dir.string() + ".log"));
  for (const char* p : {"coupler.log", "fluid.log", "solid.log"})
    s += "\n--- " + std::string(p) + ":\n" + read_text(dir / p);
  return s;
}

// What the coupler recorded of each solver from its Hello (coupler_summary.json "peers"): the MPI ranks it speaks
// for (the coupler's handshake line says it too, in a run without --quiet:
// CouplingProcesses.HelloRanksAreRecordedByTheCoupler).
inline void expect_coupler_peer_ranks(const fs::path& run, int fluid, int solid) {
  const nlohmann::json c = nlohmann::json::parse(read_text(run / "coupler" / "coupler_summary.json"));
  ASSERT_TRUE(c.contains("peers")) << c.dump();
  EXPECT_EQ(c["peers"]["fluid"]["ranks"].get<int>(), fluid) << c.dump();
  EXPECT_EQ(c["peers"]["solid"]["ranks"].get<int>(), solid) << c.dump();
  EXPECT_EQ(c["peers"]["fluid"]["program"].get<std::string>(), "fluid_solver") << c.dump();
  EXPECT_EQ(c["peers"]["solid"]["program"].get<std::string>(), "solid_solver") << c.dump();
}

// coupler/interface_history.csv: per cycle, area-weighted means over the solid's faces.
struct History {
  std::vector<double> t, dt, force_x, vx, vy, cx, cy, pressure;
  std::size_t size() const { return t.size(); }
  // Linear interpolation of the centre's x at time s.
  double cx_at(double s) const {
    if (s <= t.front()) return cx.front();
    for (std::size_t i = 1; i < t.size(); ++i)
      if (t[i] >= s) return cx[i - 1] + (cx[i] - cx[i - 1]) * (s - t[i - 1]) / (t[i] - t[i - 1]);
    return cx.back();
  }
};

inline History read_history(const fs::path& dir) {
  History h;
  std::ifstream in(dir / "coupler" / "interface_history.csv");
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    std::vector<double> v;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) v.push_back(std::strtod(cell.c_str(), nullptr));
    if (v.size() < 13) continue;
    h.t.push_back(v[1]);
    h.dt.push_back(v[2]);
    h.force_x.push_back(v[3]);
    h.vx.push_back(v[6]);
    h.vy.push_back(v[7]);
    h.cx.push_back(v[9]);
    h.cy.push_back(v[10]);
    h.pressure.push_back(v[12]);
  }
  return h;
}

// How far run b's structure moved from run a's: the largest difference of the displacements (centre_x minus
// its start) at b's times, and b's largest displacement.
struct TrajectoryDifference {
  double worst = 0, travel = 0;  // [m]
};
inline TrajectoryDifference trajectory_difference(const History& a, const History& b) {
  TrajectoryDifference d;
  for (std::size_t i = 0; i < b.size(); ++i) {
    d.worst = std::max(d.worst, std::abs((b.cx[i] - b.cx[0]) - (a.cx_at(b.t[i]) - a.cx[0])));
    d.travel = std::max(d.travel, std::abs(b.cx[i] - b.cx[0]));
  }
  return d;
}

// Total variation of a series divided by its range: about 2 per half-oscillation of a smooth signal,
// large when it rings.
inline double relative_total_variation(const std::vector<double>& v) {
  if (v.size() < 2) return 0.0;
  double tv = 0, lo = v[0], hi = v[0];
  for (std::size_t i = 1; i < v.size(); ++i) {
    tv += std::abs(v[i] - v[i - 1]);
    lo = std::min(lo, v[i]);
    hi = std::max(hi, v[i]);
  }
  return hi > lo ? tv / (hi - lo) : 0.0;
}

}  // namespace cosim::test
