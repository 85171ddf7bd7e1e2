// Embedded bodies on several ranks: each block cuts the bodies over its cells and a margin, the cells its image
// points, wall limiter and wall pressure samples read beyond its ghost layers come from their owners, and the
// snapshots, the interface segment files and the summary's accounts equal the one-rank run's (the snapshots and
// segment files bit for bit, the accounts, sums over the blocks in another order, to round-off).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "fluid_solver/core/embedded_block.h"
#include "fluid_solver/embedded/image_points.h"
#include "fluid_solver/embedded/lattice.h"
#include "tests/parallel/rank_runs.h"

namespace {

using cosim::test::RankRun;
using cosim::test::read_text;
using cosim::test::run_fluid_ranks;
using cosim::test::scene_path;
using cosim::test::scratch_path;
using cosim::test::series_difference;
using cosim::test::summary_of;

// A sphere moving along z through the block boundary of a 1 x 1 x 2 (and 1 x 2 x 2) layout at z = 0.5.
const char* kMovingSphere = R"(name: moving_sphere
fluid:
  mesh: {cells: [14, 14, 16], lower: [0.0, 0.0, 0.0], upper: [1.0, 1.0, 1.0]}
  phases: [{name: gas, eos: {type: ideal_gas, gamma: 1.4}}]
  time: {end: 0.3}
  boundaries: {x_lower: transmissive, x_upper: transmissive, y_lower: wall, y_upper: wall, z_lower: transmissive, z_upper: transmissive}
  embedded:
    bodies:
      - {shape: sphere, center: [0.5, 0.45, 0.33], radius: 0.2, segments: 2, velocity: [0.1, 0.2, 1.0]}
  initial:
    state: {rho: 1.0, velocity: [0.0, 0.0, 0.0], p: 1.0}
  output: {interval: 0.1}
)";

// A plate thinner than a cell (blocked faces, side ghosts) next to a block boundary, hit by a Mach 2 shock.
const char* kThinPlate = R"(name: thin_plate
fluid:
  mesh: {cells: [40, 30], lower: [0.0, 0.0], upper: [1.0, 0.75]}
  phases: [{name: gas, eos: {type: ideal_gas, gamma: 1.4}}]
  time: {end: 0.15}
  boundaries:
    x_lower: {type: inflow, state: {rho: 2.667, velocity: [1.25, 0.0], p: 4.5}}
    x_upper: transmissive
    y_lower: wall
    y_upper: wall
  embedded:
    bodies:
      - {shape: box, lower: [0.49, 0.15], upper: [0.505, 0.55], rotation: 10}
  initial:
    state: {rho: 1.0, velocity: [0.0, 0.0], p: 1.0}
    regions:
      - box: {lower: [0.0, 0.0], upper: [0.3, 0.75]}
        state: {rho: 2.667, velocity: [1.25, 0.0], p: 4.5}
  output: {interval: 0.075}
)";

struct Case {
  std::string name, scene, sets;
  std::vector<int> ranks;
  int dim;
  std::vector<std::string> layouts = {};  // fluid.parallel.ranks per entry of `ranks` (empty: the solver's choice)
};

std::vector<std::filesystem::path> interface_files(const std::filesystem::path& out) {
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(out))
    if (e.path().filename().string().rfind("fluid_interface_", 0) == 0) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

// The one-rank run against N ranks: ranks and layout real, snapshots and segment files bit for bit, the embedded
// accounts equal to round-off and the ghost cells counted once.
void expect_as_one_rank(const Case& c) {
  const auto one = scratch_path("emb_" + c.name + "_1");
  const RankRun r1 = run_fluid_ranks(1, c.scene, one, c.sets);
  ASSERT_EQ(r1.code, 0) << c.name << "\n" << r1.log;
  const nlohmann::json s1 = summary_of(one);
  ASSERT_TRUE(s1.contains("embedded")) << c.name;
  const auto files1 = interface_files(one);
  ASSERT_FALSE(files1.empty()) << c.name << ": no interface segment files";
  for (const int& n : c.ranks) {
    const std::size_t at = static_cast<std::size_t>(&n - c.ranks.data());
    const std::string layout = c.layouts.empty() ? "" : " --set fluid.parallel.ranks=" + c.layouts[at];
    const std::string what = c.name + " on " + std::to_string(n) + " ranks" + layout;
    const auto out = scratch_path("emb_" + c.name + "_" + std::to_string(n) + "_" + std::to_string(at));
    const RankRun r = run_fluid_ranks(n, c.scene, out, c.sets + layout);
    ASSERT_EQ(r.code, 0) << what << "\n" << r.log;
    const nlohmann::json s = summary_of(out);
    ASSERT_TRUE(s.contains("parallel")) << what;
    EXPECT_EQ(s["parallel"]["ranks"].get<int>(), n) << what;
    int blocks = 1;
    for (int b : s["parallel"]["layout"].get<std::vector<int>>()) blocks *= b;
    EXPECT_EQ(blocks, n) << what;
    EXPECT_GT(s["parallel"]["halo_bytes"].get<double>(), 0.0) << what;
    EXPECT_EQ(s["steps"], s1["steps"]) << what;
    EXPECT_EQ(series_difference(one, out), "") << what;
    const auto files = interface_files(out);
    ASSERT_EQ(files.size(), files1.size()) << what;
    for (std::size_t i = 0; i < files.size(); ++i)
      EXPECT_TRUE(read_text(files[i]) == read_text(files1[i])) << what << ": " << files[i].filename();
    const nlohmann::json &e1 = s1["embedded"], &e = s["embedded"];
    EXPECT_EQ(e["ghost_and_solid_cut_cells"].get<double>(), e1["ghost_and_solid_cut_cells"].get<double>()) << what;
    const double m = std::abs(s1["totals"]["end"][0]["mass"].get<double>());
    for (std::size_t k = 0; k < e1["mass"].size(); ++k)
      for (const char* key : {"through_walls", "cells_uncovered"})
        EXPECT_NEAR(e["mass"][k][key].get<double>(), e1["mass"][k][key].get<double>(), 1e-13 * m) << what << " " << key;
    for (std::size_t k = 0; k < e1["flow_totals_change"].size(); ++k) {
      EXPECT_NEAR(e["flow_totals_change"][k]["mass"].get<double>(), e1["flow_totals_change"][k]["mass"].get<double>(),
                  1e-13 * m)
          << what;
      const double en = std::abs(s1["totals"]["end"][k]["energy"].get<double>());
      EXPECT_NEAR(e["flow_totals_change"][k]["energy"].get<double>(),
                  e1["flow_totals_change"][k]["energy"].get<double>(), 1e-13 * en)
          << what;
    }
    // The wall faces' exchange, each face counted on the block that owns its flow cell.
    ASSERT_EQ(e["wall_exchange"].size(), e1["wall_exchange"].size()) << what;
    double force = 0;
    for (std::size_t k = 0; k < e1["wall_exchange"].size(); ++k) {
      const nlohmann::json &w1 = e1["wall_exchange"][k], &w = e["wall_exchange"][k];
      const double en = std::abs(s1["totals"]["end"][k]["energy"].get<double>());
      const double p = std::sqrt(2.0 * m * en);  // a momentum scale
      EXPECT_NEAR(w["mass"].get<double>(), w1["mass"].get<double>(), 1e-13 * m) << what;
      EXPECT_NEAR(w["energy"].get<double>(), w1["energy"].get<double>(), 1e-13 * en) << what;
      for (int d = 0; d < 3; ++d) {
        EXPECT_NEAR(w["momentum"][d].get<double>(), w1["momentum"][d].get<double>(), 1e-13 * p) << what;
        force += std::abs(w1["momentum"][d].get<double>());
      }
    }
    EXPECT_GT(force, 0.0) << what << ": the walls exchanged no momentum";
    std::printf("[ measured ] %s (layout %s): bit for bit, %.2f s (one rank %.2f s), embedded exchange %.0f bytes\n",
                what.c_str(), s["parallel"]["layout"].dump().c_str(), r.seconds, r1.seconds,
                s["parallel"].value("embedded_exchange_bytes", 0.0));
  }
}

TEST(EmbeddedRanks, SupersonicCylinderEqualsTheOneRankRun) {
  expect_as_one_rank({"cylinder",
                      scene_path("supersonic_cylinder"),
                      "--set fluid.mesh.cells=[60,60] --set fluid.time.end=0.2 --set fluid.output.interval=0.1",
                      {2, 3, 4},
                      2});
}

TEST(EmbeddedRanks, AdvectedBoxEqualsTheOneRankRun) {  // a moving body across blocks and the periodic seams
  expect_as_one_rank({"advection",
                      scene_path("embedded_advection"),
                      "--set fluid.time.end=3.0 --set fluid.output.interval=1.5",
                      {2, 3, 4},
                      2});
}

TEST(EmbeddedRanks, LowMachStepEqualsTheOneRankRun) {
  expect_as_one_rank({"step",
                      scene_path("low_mach_step"),
                      "--set fluid.mesh.cells=[64,32] --set fluid.time.end=0.6 --set fluid.output.interval=0.3",
                      {2, 3, 4},
                      2});
}

// Blocks with no blocked face of their own (4 x 1: the plate in blocks 1 and 2) must still apply their x faces as
// the mesh with blocked faces does (EmbeddedState::blocked_x): the same sums, bit for bit.
TEST(EmbeddedRanks, AThinPlateNextToBlockBoundariesEqualsTheOneRankRun) {
  expect_as_one_rank({"thin_plate",
                      cosim::test::write_scene("thin_plate", kThinPlate),
                      "",
                      {2, 3, 4, 4},
                      2,
                      {"[2,1]", "[3,1]", "[4,1]", "[2,2]"}});
}

TEST(EmbeddedRanks, ASphereMovingAcrossTheRankBoundaryIn3DEqualsTheOneRankRun) {
  expect_as_one_rank({"sphere", cosim::test::write_scene("moving_sphere", kMovingSphere), "", {2, 3, 4}, 3});
}

// A moving sphere's set written on 2 ranks restarts on 3 (and one on 3 on 1): the bodies' vertices go with the state,
// and the run ends as the uninterrupted one-rank run, bit for bit.
void expect_restarts_on_other_rank_counts(const std::string& tag_prefix, const std::string& extra) {
  const std::string scene = cosim::test::write_scene(tag_prefix + "moving_sphere_restart", kMovingSphere);
  const std::string sets = "--set fluid.time.end=0.2 --set 'fluid.checkpoint={interval: 0.1, keep: 2}'" + extra;
  const auto whole = scratch_path("emb_restart_" + tag_prefix + "whole");
  ASSERT_EQ(run_fluid_ranks(1, scene, whole, sets).code, 0);
  for (const auto& [from, to] : std::vector<std::pair<int, int>>{{2, 3}, {3, 1}}) {
    const std::string tag = tag_prefix + std::to_string(from) + "_to_" + std::to_string(to);
    const auto first = scratch_path("emb_restart_" + tag);
    const RankRun a = run_fluid_ranks(from, scene, first, sets + " --set fluid.time.end=0.1");
    ASSERT_EQ(a.code, 0) << a.log;
    std::filesystem::path newest;
    for (const auto& e : std::filesystem::directory_iterator(first / "checkpoints"))
      if (e.is_directory() && e.path() > newest) newest = e.path();
    ASSERT_FALSE(newest.empty()) << a.log;
    const RankRun b = run_fluid_ranks(to, scene, first, sets + " --restart " + newest.string());
    ASSERT_EQ(b.code, 0) << b.log;
    EXPECT_EQ(series_difference(whole, first), "") << tag;
    EXPECT_EQ(summary_of(first)["parallel"]["ranks"].get<int>(), to) << tag;
  }
}

TEST(EmbeddedRanks, ACheckpointWithAMovingBodyRestartsOnAnotherRankCount) {
  expect_restarts_on_other_rank_counts("", "");
}

// The conservative boundary (fluid.embedded.conservative) with a moving body crossing the block seams (and the
// periodic ones): the fluid volumes and the covered and uncovered cells' exchanges with the cells of other blocks
// are those of one rank, bit for bit, on 2 and 3 ranks; the mass, which no wall face passes, stays to round-off.
TEST(EmbeddedRanks, TheConservativeBoundaryWithAMovingBodyEqualsTheOneRankRun) {
  const std::string sets =
      "--set fluid.time.end=3.0 --set fluid.output.interval=1.5 --set fluid.embedded.conservative=true";
  expect_as_one_rank({"conservative_advection", scene_path("embedded_advection"), sets, {2, 3}, 2});
  for (const int n : {1, 3}) {
    // expect_as_one_rank's output folders (scratch_path would empty them)
    const auto out =
        cosim::test::scratch_root() / ("emb_conservative_advection_" + std::to_string(n) + (n == 1 ? "" : "_1"));
    const nlohmann::json s = summary_of(out);
    EXPECT_TRUE(s["embedded"]["conservative"].get<bool>());
    const double m0 = s["totals"]["start"][0]["mass"].get<double>(), m1 = s["totals"]["end"][0]["mass"].get<double>();
    const double wall = s["embedded"]["mass"][0]["through_walls"].get<double>();
    const double cells = s["embedded"]["mass"][0]["cells_uncovered"].get<double>();
    EXPECT_NEAR(m1 - m0, wall + cells, 1e-12 * m0) << n << " ranks";
    EXPECT_NEAR(wall, 0.0, 1e-12 * m0) << n << " ranks";
  }
}

// The moving sphere in 3D with the conservative boundary on 2 ranks (1 x 1 x 2: it crosses the seam at z = 0.5).
TEST(EmbeddedRanks, TheConservativeBoundaryWithAMovingSphereIn3DEqualsTheOneRankRun) {
  expect_as_one_rank({"conservative_sphere",
                      cosim::test::write_scene("moving_sphere_conservative", kMovingSphere),
                      "--set fluid.embedded.conservative=true",
                      {2},
                      3});
}

// The same restarts with the conservative boundary: a set's cells hold the contents of its geometry, and the ranks
// that resume it take the volumes of the ghost layers from their owners before the first step.
TEST(EmbeddedRanks, TheConservativeBoundaryRestartsOnAnotherRankCount) {
  expect_restarts_on_other_rank_counts("conservative_", " --set fluid.embedded.conservative=true");
}

// The reach check: an image point whose stencil lies beyond the cells a block's lattice holds is an error naming
// the cell, where the whole mesh's lattice (the same point) clamps it to its edge as before.
TEST(EmbeddedReach, AnImagePointBeyondTheBlocksCellsIsAnError) {
  using namespace cosim::fluid;
  const Grid<2> whole({20, 20, 1}, {0, 0, 0}, {1, 1, 1});
  const Grid<2> block = sub_grid(whole, {5, 5, 0}, {4, 4, 1});
  embedded::ImagePoint ip;
  ip.x_image = {0.5 * 0.05, 14.5 * 0.05, 0};  // the centre of cell (0, 14): beyond the block's padded cells in y
  double w = 0;
  const auto all = [](std::size_t) { return true; };
  EXPECT_THROW(embedded::detail::build_stencil(embedded::centre_lattice(block), all, ip, w), embedded::ReachError);
  EXPECT_NO_THROW(embedded::detail::build_stencil(embedded::centre_lattice(whole), all, ip, w));
  EXPECT_DOUBLE_EQ(w, 1.0);
  // Inside the block's padded cells, the block's stencil names the same cells as the whole mesh's.
  ip.x_image = {6.7 * 0.05, 7.2 * 0.05, 0};
  embedded::ImagePoint a = ip, b = ip;
  embedded::detail::build_stencil(embedded::centre_lattice(block), all, a, w);
  embedded::detail::build_stencil(embedded::centre_lattice(whole), all, b, w);
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(block.global_ijk(a.stencil[k]), whole.global_ijk(b.stencil[k]));
    EXPECT_EQ(a.bilinear[k], b.bilinear[k]);
  }
  // The margin grid covers every reach (reach.h), clipped to the mesh.
  const Grid<2> big({60, 60, 1}, {0, 0, 0}, {1, 1, 1});
  const Grid<2> mid = sub_grid(big, {25, 25, 0}, {4, 4, 1}), m = margin_grid(mid), edge = margin_grid(block);
  const int margin = embedded::margin_cells<2>(mid.dx, 0, Grid<2>::NG);
  EXPECT_EQ(mid.first[0] - m.first[0], margin);
  EXPECT_EQ(m.n[0], 4 + 2 * margin);
  EXPECT_GE(margin, Grid<2>::NG + embedded::image_point_reach<2>(mid.dx, 0));
  EXPECT_GE(margin, Grid<2>::NG + embedded::sample_reach<2>(mid.dx, 0));
  EXPECT_GE(margin, Grid<2>::NG + embedded::kWallLimiterReach);
  EXPECT_EQ(edge.first[0], 0);
  EXPECT_EQ(edge.first[0] + edge.n[0], 20);
}

}  // namespace
