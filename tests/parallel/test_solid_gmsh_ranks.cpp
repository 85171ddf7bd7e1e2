// A solid on a Gmsh mesh over several ranks: rank 0 alone reads the file and broadcasts the parsed mesh. The ranks
// other than 0 are started (mpirun's MPMD form, "A : B") with the mesh file named as a path that does not exist, so
// that the run fails if any of them opens it; the snapshots and block history of 2 and 3 ranks equal the one-rank
// run's bit for bit. A corrupt or missing file ends every rank with code 2 and rank 0's file:line message, no hang.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/parallel/rank_runs.h"

using cosim::test::RankRun;
using cosim::test::read_text;
using cosim::test::scratch_path;
using cosim::test::series_difference;
using cosim::test::summary_of;
namespace fs = std::filesystem;

namespace {

// The steel panel of configs/shock_panel_2d_gmsh.yaml (configs/meshes/panel_5x25.msh), clamped at both ends and
// loaded by a pressure on its front, ramped over 20 us: it bends.
const char* kPanel = R"(name: panel_gmsh
solid:
  mesh: {type: gmsh, file: panel.msh}
  blocks:
    - name: panel
      material: steel
      strength: {shear_modulus: 7.77e10, yield_stress: 7.92e8}
  boundaries:
    - {set: clamp_bottom, type: fixed}
    - {set: clamp_top, type: fixed}
    - {set: front, type: pressure, value: 2.0e8, ramp: 2.0e-5}
  time: {end: 1.0e-4}
  output: {interval: 5.0e-5, history_every: 5}
)";

const fs::path kPanelMesh = fs::path(COSIM_SOURCE_DIR) / "configs" / "meshes" / "panel_5x25.msh";

// The panel scene in its own folder, next to `mesh_text` as panel.msh.
std::string panel_scene(const std::string& name, const std::string& mesh_text) {
  const std::string scene = cosim::test::write_scene(name, kPanel);
  std::ofstream(fs::path(scene).parent_path() / "panel.msh") << mesh_text;
  return scene;
}

std::string solver() { return std::string(COSIM_BINARY_DIR) + "/bin/solid_solver"; }

// mpirun's MPMD form: rank 0 runs `args`, ranks 1 .. ranks-1 run `args` + `others` (each part a shell word list).
RankRun run_mpmd(int ranks, const std::string& args, const std::string& others, const fs::path& log, int limit_s) {
  return cosim::test::run_timed("mpirun --allow-run-as-root --oversubscribe --bind-to none -np 1 " + args + " : -np " +
                                    std::to_string(ranks - 1) + " " + args + " " + others,
                                log, limit_s);
}

std::size_t count_of(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

}  // namespace

TEST(SolidGmshRanks, OnlyRankZeroReadsTheMeshAndTheRunsEqualTheOneRankRunBitForBit) {
  const std::string scene = panel_scene("panel_gmsh", read_text(kPanelMesh));
  const fs::path missing = fs::path(scene).parent_path() / "not_here" / "panel.msh";
  ASSERT_FALSE(fs::exists(missing));
  const auto one = scratch_path("solid_gmsh_1");
  const RankRun r1 = cosim::test::run_solid_ranks(1, scene, one, "", 120);
  ASSERT_EQ(r1.code, 0) << r1.log;
  const nlohmann::json s1 = summary_of(one);
  EXPECT_FALSE(s1["parallel"].contains("mesh")) << "one rank reads the file itself";
  for (int n : {2, 3}) {
    const std::string what = "the Gmsh panel on " + std::to_string(n) + " ranks";
    const auto out = scratch_path("solid_gmsh_" + std::to_string(n));
    const std::string args = solver() + " " + scene + " --out " + out.string() + " --quiet --threads 1";
    const RankRun r = run_mpmd(n, args, "--set solid.mesh.file=" + missing.string(), out.string() + ".log", 120);
    ASSERT_EQ(r.code, 0) << what << "\n" << r.log;
    EXPECT_EQ(series_difference(one, out, "solid_"), "") << what;
    EXPECT_EQ(read_text(one / "block_history.csv"), read_text(out / "block_history.csv")) << what;
    const nlohmann::json s = summary_of(out);
    EXPECT_EQ(s["steps"].get<long>(), s1["steps"].get<long>()) << what;
    const nlohmann::json& p = s["parallel"];
    EXPECT_EQ(p["ranks"].get<int>(), n) << what;
    const auto elements = p["elements_per_rank"].get<std::vector<long>>();
    ASSERT_EQ(static_cast<int>(elements.size()), n) << what;
    for (long e : elements) EXPECT_GT(e, 0) << what << ": a rank owns no element";
    EXPECT_GT(p["halo_bytes"].get<double>(), 0.0) << what;
    ASSERT_TRUE(p.contains("mesh")) << s.dump(2);
    EXPECT_EQ(p["mesh"]["read_by_ranks"].get<std::vector<int>>(), std::vector<int>{0}) << what;
    EXPECT_EQ(p["mesh"]["file"].get<std::string>(), (fs::path(scene).parent_path() / "panel.msh").string());
    // The packed mesh: 156 nodes x 2 doubles, 125 x (4 + 1) ints and the sets, corner lists and names.
    EXPECT_GT(p["mesh"]["bytes"].get<double>(), 156 * 16 + 125 * 20) << what;
    EXPECT_LT(p["mesh"]["bytes"].get<double>(), 16000) << what;
    std::printf(
        "[ measured ] %s: the mesh read by rank 0 only (the others given %s), %.0f bytes broadcast, "
        "snapshots equal bit for bit\n",
        what.c_str(), (missing.parent_path().filename() / missing.filename()).c_str(),
        p["mesh"]["bytes"].get<double>());
  }
  // The control: the missing path given to every rank ends the run, so the ranks above did not read it.
  const auto all = scratch_path("solid_gmsh_missing_everywhere");
  const RankRun m = cosim::test::run_solid_ranks(2, scene, all, "--set solid.mesh.file=" + missing.string(), 60);
  EXPECT_EQ(m.code, 2) << m.log;
  EXPECT_NE(m.log.find(missing.string() + ": cannot open the Gmsh mesh file"), std::string::npos) << m.log;
}

// A coordinate that is no number: every rank ends with code 2 (each rank's own exit code recorded by a shell around
// it), rank 0's message naming the file and line printed once, no output folder, within seconds.
TEST(SolidGmshRanks, ACorruptMeshEndsEveryRankWithRankZerosMessage) {
  std::vector<std::string> lines;
  {
    std::istringstream in(read_text(kPanelMesh));
    for (std::string l; std::getline(in, l);) lines.push_back(l);
  }
  std::size_t nodes = 0;
  while (nodes < lines.size() && lines[nodes] != "$Nodes") ++nodes;
  ASSERT_LT(nodes, lines.size());
  const std::size_t bad = nodes + 3 + 156 + 39;  // the coordinates of node 40 (after the headers and 156 tags)
  lines[bad] = "0.5 not-a-number 0";
  std::string text;
  for (const auto& l : lines) text += l + "\n";
  const std::string scene = panel_scene("panel_gmsh_corrupt", text);
  const std::string file = (fs::path(scene).parent_path() / "panel.msh").string();
  const std::string message = file + ":" + std::to_string(bad + 1) + ": expected node coordinates 'x y z'";

  const auto out = scratch_path("solid_gmsh_corrupt");
  const RankRun r = cosim::test::run_solid_ranks(2, scene, out, "", 60);
  EXPECT_EQ(r.code, 2) << r.log;
  EXPECT_EQ(count_of(r.log, message), 1u) << r.log;
  EXPECT_NE(r.log.find("solid.mesh.file: " + message), std::string::npos) << r.log;
  EXPECT_FALSE(fs::exists(out)) << "an output folder for a run that could not start";
  EXPECT_LT(r.seconds, 30.0) << r.log;

  // Each rank's exit code, through a shell that records it and exits 0 (so that mpirun ends no rank early).
  const auto codes = scratch_path("solid_gmsh_corrupt_codes");
  fs::create_directories(codes);
  const std::string rank_cmd = "bash -c '" + solver() + " " + scene + " --out " + (codes / "out").string() +
                               " --quiet --threads 1; echo $? > " + codes.string() + "/rc.$OMPI_COMM_WORLD_RANK'";
  const std::string cmd = "timeout -s KILL 60 mpirun --allow-run-as-root --oversubscribe --bind-to none -np 2 " +
                          rank_cmd + " > " + codes.string() + ".log 2>&1";
  EXPECT_EQ(WEXITSTATUS(std::system(cmd.c_str())), 0) << read_text(codes.string() + ".log");
  for (int rank : {0, 1}) {
    const fs::path rc = codes / ("rc." + std::to_string(rank));
    ASSERT_TRUE(fs::exists(rc)) << "rank " << rank << " did not end\n" << read_text(codes.string() + ".log");
    EXPECT_EQ(std::stoi(read_text(rc)), 2) << "rank " << rank;
  }
  std::printf("[ measured ] a corrupt Gmsh file on 2 ranks: code 2 from every rank in %.2f s\n", r.seconds);
}

// A missing file on 2 ranks: rank 0's "cannot open" message, code 2.
TEST(SolidGmshRanks, AMissingMeshEndsEveryRank) {
  const std::string scene = cosim::test::write_scene("panel_gmsh_missing", kPanel);
  const std::string file = (fs::path(scene).parent_path() / "panel.msh").string();
  const auto out = scratch_path("solid_gmsh_missing");
  const RankRun r = cosim::test::run_solid_ranks(2, scene, out, "", 60);
  EXPECT_EQ(r.code, 2) << r.log;
  EXPECT_EQ(count_of(r.log, file + ": cannot open the Gmsh mesh file"), 1u) << r.log;
  EXPECT_LT(r.seconds, 30.0) << r.log;
}
