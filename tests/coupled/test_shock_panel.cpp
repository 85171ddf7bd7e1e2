// Paper 9.5, a blast on a clamped steel panel (configs/shock_panel_2d.yaml): the embedded run (fluid_solver +
// solid_solver + coupler) against the conforming one (configs/shock_panel_2d_conforming.yaml: one body-fitted
// solid_solver mesh, ALE air). The measure is the paper's (Fig. 9b): the panel's mass-averaged velocity over the
// whole run, from solid/block_history.csv of each.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "common/io/hdf5_file.h"
#include "coupled_test_util.h"

using namespace cosim;
using namespace cosim::test;

namespace {

struct VelocityHistory {
  std::vector<double> t, v;  // panel mean x velocity [m/s]
  double at(double s) const {
    if (s <= t.front()) return v.front();
    for (std::size_t i = 1; i < t.size(); ++i)
      if (t[i] >= s) return v[i - 1] + (v[i] - v[i - 1]) * (s - t[i - 1]) / (t[i] - t[i - 1]);
    return v.back();
  }
  double peak() const {
    double p = 0;
    for (double x : v) p = std::max(p, std::abs(x));
    return p;
  }
};

VelocityHistory panel_history(const fs::path& csv) {
  VelocityHistory h;
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::vector<std::string> c;
    for (std::string cell; std::getline(ss, cell, ',');) c.push_back(cell);
    if (c.size() < 5 || c[2] != "panel") continue;
    h.t.push_back(std::stod(c[0]));
    h.v.push_back(std::stod(c[4]));
  }
  return h;
}

// Background n x n with the panel n/10 x n/2; conforming mesh of the same element size.
VelocityHistory embedded(int n) {
  const fs::path dir = run_dir("shock_panel_" + std::to_string(n));
  const std::string set = "--set fluid.mesh.cells=[" + std::to_string(n) + "," + std::to_string(n) +
                          "] --set solid.mesh.cells=[" + std::to_string(n / 10) + "," + std::to_string(n / 2) + "]";
  EXPECT_EQ(cosim_run(scene_file("shock_panel_2d"), dir, set), 0) << run_logs(dir);
  return panel_history(dir / "solid" / "block_history.csv");
}

VelocityHistory conforming(int n) {
  const fs::path dir = run_dir("shock_panel_conforming_" + std::to_string(n));
  // 50: the scene's own box (51 elements on [-0.01, 1.01]); 100 and 200: [0, 1].
  const std::string set = n == 50 ? ""
                                  : " --set solid.mesh.cells=[" + std::to_string(n) + "," + std::to_string(n) +
                                        "] --set solid.mesh.lower=[0,0] --set solid.mesh.upper=[1,1]";
  const std::string cmd = bin("solid_solver").string() + " " + scene_file("shock_panel_2d_conforming").string() +
                          " --out " + dir.string() + " --quiet" + set + " > " + dir.string() + ".log 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << read_text(fs::path(dir.string() + ".log"));
  return panel_history(dir / "block_history.csv");
}

std::string fmt_snapshot(int k) {
  char name[32];
  std::snprintf(name, sizeof name, "fluid_%06d.h5", k);
  return name;
}

}  // namespace

// The embedded and the conforming panel velocity histories converge to each other: the largest difference over
// the whole run (0 to 1 ms) against the conforming run's peak shrinks with the resolution and is within 10% at
// 200 x 200 (measured 30% / 18% / 8.6% at 50^2 / 100^2 / 200^2: at the paper's 50 x 50 the hot region is five
// cells across and neither run resolves the blast; peaks 25.1 / 28.2 / 26.9 m/s embedded, 21 / 24 / 25.2
// conforming; with the paper's wall velocity extrapolated across the shock the embedded 50^2 peak was 34.8 m/s,
// 71% apart).
TEST(ShockPanel, EmbeddedAndConformingPanelVelocityConverge) {
  double previous = 1e9;
  for (int n : {50, 100, 200}) {
    const VelocityHistory e = embedded(n), c = conforming(n);
    ASSERT_GT(e.t.size(), 100u);
    ASSERT_GT(c.t.size(), 100u);
    EXPECT_NEAR(e.t.back(), 1e-3, 1e-9);
    EXPECT_NEAR(c.t.back(), 1e-3, 1e-9);
    double worst = 0, when = 0;
    for (int k = 0; k <= 1000; ++k) {
      const double s = 1e-6 * k, d = std::abs(e.at(s) - c.at(s));
      if (d > worst) worst = d, when = s;
    }
    const double rel = worst / c.peak();
    std::printf(
        "[ measured ] panel %d^2: peak mean velocity embedded %.2f m/s, conforming %.2f m/s; largest "
        "difference %.2f m/s at %.3f ms (%.1f%% of the conforming peak)\n",
        n, e.peak(), c.peak(), worst, 1e3 * when, 100 * rel);
    EXPECT_LT(rel, previous);
    previous = rel;
    if (n == 200) { EXPECT_LT(rel, 0.10); }
    // The panel swings back: its most negative mean velocity is a third to a half of the peak in both runs.
    double ve = 0, vc = 0;
    for (double v : e.v) ve = std::min(ve, v);
    for (double v : c.v) vc = std::min(vc, v);
    EXPECT_LT(ve, -0.25 * e.peak());
    EXPECT_LT(vc, -0.25 * c.peak());
  }
}

// The paper's 50 x 50, the scene as shipped (second-order walls, embedded.order: 2) and first-order walls beside
// it, to just past the peak of the panel's mean x velocity (0.23 ms). The panel's faces pass through cell centres
// (d = 0, the largest half-cell extrapolation of the wall velocity), and the blast's reflected shock, spread by
// MUSCL over the three cells next to the blast face, gave slopes the paper's two-difference minmod did not limit:
// the peak was 34.8 m/s, 37% above the converged one (docs/deformable_structures.md, "Wall order at 50 x 50");
// second order now takes the wall's velocity where a shock lies in the four cells next to the wall. Reference:
// the scene with fluid.mesh.cells=[200,200] and nothing else changed, 25.46 m/s at 0.229 ms with first-order
// walls and 25.43 with second-order ones (bench/coupled/run_panel_orders.py --fixed-panel). Measured now:
// 25.08 m/s (second order), 25.02 (first order). Second order must be within 10% of it and no further from it than first order
// (2% of the reference allowed for round-off in where the two runs' peaks fall).
TEST(ShockPanel, SecondOrderWallsAtThePapersResolutionAsAccurateAsFirstOrder) {
  constexpr double kReference200 = 25.46;  // [m/s], 200 x 200 background, panel 5 x 25
  const std::string shorter = "--set coupling.time.end=2.6e-4";
  double peak[2] = {0, 0};
  for (int order : {1, 2}) {
    const fs::path dir = run_dir("shock_panel_50_order" + std::to_string(order));
    ASSERT_EQ(
        cosim_run(scene_file("shock_panel_2d"), dir, shorter + " --set fluid.embedded.order=" + std::to_string(order)),
        0)
        << run_logs(dir);
    const VelocityHistory h = panel_history(dir / "solid" / "block_history.csv");
    ASSERT_GT(h.t.size(), 20u);
    for (double v : h.v) peak[order - 1] = std::max(peak[order - 1], v);
  }
  const double e1 = std::abs(peak[0] - kReference200) / kReference200;
  const double e2 = std::abs(peak[1] - kReference200) / kReference200;
  std::printf(
      "[ measured ] panel 50^2 peak mean velocity: first-order walls %.2f m/s (%.1f%% from 200^2), second-order "
      "%.2f m/s (%.1f%%)\n",
      peak[0], 100 * e1, peak[1], 100 * e2);
  EXPECT_LT(e2, 0.10);
  EXPECT_LE(e2, e1 + 0.02);
}

// The panel from a Gmsh file named relative to the scene (configs/shock_panel_2d_gmsh.yaml), run through
// `cosim run` from another working directory: the mesh is found next to the scene the user gave (not next to the
// copy in the run directory), and the run is the box-mesh scene's to round-off. A missing mesh file stops the
// run with exit code 2 and a message naming the key and the path.
TEST(ShockPanel, GmshVariantThroughCosimRunMatchesTheBoxMesh) {
  const fs::path gdir = run_dir("shock_panel_gmsh"), bdir = run_dir("shock_panel_box");
  const std::string shorter = "--set coupling.time.end=1e-4";
  const std::string cd = "cd " + fs::temp_directory_path().string() + " && ";
  const std::string cmd = cd + bin("cosim").string() + " run " + scene_file("shock_panel_2d_gmsh").string() +
                          " --out " + gdir.string() + " --quiet " + shorter + " > " + gdir.string() + ".log 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << run_logs(gdir);
  ASSERT_EQ(cosim_run(scene_file("shock_panel_2d"), bdir, shorter), 0) << run_logs(bdir);
  const VelocityHistory g = panel_history(gdir / "solid" / "block_history.csv");
  const VelocityHistory b = panel_history(bdir / "solid" / "block_history.csv");
  ASSERT_EQ(g.t.size(), b.t.size());
  ASSERT_GT(b.peak(), 1.0);
  double worst = 0;
  for (std::size_t i = 0; i < g.t.size(); ++i) worst = std::max(worst, std::abs(g.v[i] - b.v[i]));
  std::printf("[ measured ] Gmsh panel vs box panel: %zu history rows, largest velocity difference %.2e m/s\n",
              g.t.size(), worst);
  EXPECT_LT(worst, 1e-9 * b.peak());

  const fs::path mdir = run_dir("shock_panel_gmsh_missing");
  const std::string bad = cd + bin("cosim").string() + " run " + scene_file("shock_panel_2d_gmsh").string() +
                          " --out " + mdir.string() + " --quiet --set solid.mesh.file=meshes/missing.msh > " +
                          mdir.string() + ".log 2>&1";
  const int rc = std::system(bad.c_str());
  ASSERT_TRUE(WIFEXITED(rc));
  EXPECT_EQ(WEXITSTATUS(rc), 2);
  const std::string log = run_logs(mdir);
  EXPECT_NE(log.find("solid.mesh.file"), std::string::npos) << log;
  EXPECT_NE(log.find((fs::path(COSIM_SOURCE_DIR) / "configs" / "meshes" / "missing.msh").string()), std::string::npos)
      << log;
}

// At the paper's 50 x 50 the panel's faces pass through cell centres and its clamped corner nodes sit on cell
// centres. The solid cell there takes the normal of one of the faces meeting at the corner; across the grid face
// parallel to that normal its mirror must still be a wall (core/wall_faces.h), or the flow cell beside it loses its
// mass but not its pressure (measured to 0.3 ms, before: 390,000 K and 16 km/s; after: 12,500 K and 3.5 km/s;
// over the whole run the panel shifted by a quarter cell reaches 8,800 K and 3.6 km/s).
TEST(ShockPanel, NoRunawayCellAtTheClampedCornersOnCellCentres) {
  const fs::path dir = run_dir("shock_panel_corner");
  ASSERT_EQ(cosim_run(scene_file("shock_panel_2d"), dir, "--set coupling.time.end=3e-4"), 0) << run_logs(dir);
  double t_max = 0, u_max = 0;
  for (int k = 0; fs::exists(dir / "fluid" / fmt_snapshot(k)); ++k) {
    io::Hdf5File h(dir / "fluid" / fmt_snapshot(k), io::Hdf5File::Mode::ReadOnly);
    const auto cat = h.read_doubles("/cell/embedded_category"), temp = h.read_doubles("/cell/air_temperature");
    const auto vel = h.read_doubles("/cell/air_velocity");
    for (std::size_t c = 0; c < cat.size(); ++c) {
      if (cat[c] > 1) continue;
      t_max = std::max(t_max, temp[c]);
      u_max = std::max(u_max, std::hypot(vel[3 * c], vel[3 * c + 1]));
    }
  }
  std::printf("[ measured ] panel 50^2 to 0.3 ms: hottest flow cell %.0f K, fastest %.0f m/s\n", t_max, u_max);
  EXPECT_LT(t_max, 5e4);
  EXPECT_LT(u_max, 5e3);
}
