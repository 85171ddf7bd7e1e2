// Gmsh 4.1 ASCII reader: a hand-written 2D two-block mesh (tests/solid/data/two_blocks_2d.msh), a generated
// 3D hexahedral strip, and bad files (unsupported element type, missing group, inverted and degenerate
// elements, boundary element that is no element face): each error names the file:line and the element/group.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include "solid_solver/mesh/element_faces.h"
#include "solid_solver/mesh/gmsh_reader.h"
#include "solid_test_util.h"

using namespace cosim::solid;
namespace fs = std::filesystem;

namespace {
const std::string kData = std::string(COSIM_SOURCE_DIR) + "/tests/solid/data/";

// n x 1 x 1 hexahedra on [0, n] x [0, 1]^2: volume group "body", surface groups "x_min" and "x_max".
// `edit` may change the element lines (index = element, 0-based) before they are written.
std::string hex_strip(int n, const std::function<void(std::vector<std::array<int, 8>>&)>& edit = {}) {
  auto tag = [&](int i, int j, int k) { return 1 + i + (n + 1) * (j + 2 * k); };
  std::string s =
      "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n3\n2 1 \"x_min\"\n2 2 \"x_max\"\n"
      "3 3 \"body\"\n$EndPhysicalNames\n$Entities\n0 0 2 1\n1 0 0 0 0 1 1 1 1 0\n"
      "2 0 0 0 0 1 1 1 2 0\n1 0 0 0 1 1 1 1 3 0\n$EndEntities\n";
  const int nn = 4 * (n + 1);
  s += fmt::format("$Nodes\n1 {} 1 {}\n3 1 0 {}\n", nn, nn, nn);
  for (int t = 1; t <= nn; ++t) s += fmt::format("{}\n", t);
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i <= n; ++i) s += fmt::format("{} {} {}\n", i, j, k);
  s += "$EndNodes\n";
  std::vector<std::array<int, 8>> hex;
  for (int i = 0; i < n; ++i)
    hex.push_back({tag(i, 0, 0), tag(i + 1, 0, 0), tag(i + 1, 1, 0), tag(i, 1, 0), tag(i, 0, 1), tag(i + 1, 0, 1),
                   tag(i + 1, 1, 1), tag(i, 1, 1)});
  if (edit) edit(hex);
  s += fmt::format("$Elements\n3 {} 1 {}\n2 1 3 1\n1 {} {} {} {}\n2 2 3 1\n2 {} {} {} {}\n3 1 5 {}\n", n + 2, n + 2,
                   tag(0, 0, 0), tag(0, 1, 0), tag(0, 1, 1), tag(0, 0, 1), tag(n, 0, 0), tag(n, 0, 1), tag(n, 1, 1),
                   tag(n, 1, 0), n);
  for (int i = 0; i < n; ++i) {
    s += std::to_string(i + 3);
    for (int a = 0; a < 8; ++a) s += fmt::format(" {}", hex[i][a]);
    s += "\n";
  }
  return s + "$EndElements\n";
}

std::string write_tmp(const std::string& name, const std::string& text) {
  const fs::path p = fs::temp_directory_path() / ("solid_gmsh_" + name);
  std::ofstream(p) << text;
  return p.string();
}

std::string error_of(const std::string& path) {
  try {
    read_gmsh(path);
  } catch (const MeshError& e) { return e.what(); }
  return "";
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

std::string replace(std::string s, const std::string& a, const std::string& b) {
  const auto p = s.find(a);
  EXPECT_NE(p, std::string::npos) << a;
  return s.replace(p, a.size(), b);
}
}  // namespace

TEST(SolidGmsh, Reads2DBlocksAndBoundarySets) {
  const Mesh m = read_gmsh(kData + "two_blocks_2d.msh");
  EXPECT_EQ(m.dim, 2);
  EXPECT_EQ(m.num_nodes, 6);
  EXPECT_EQ(m.num_elements, 2);
  ASSERT_EQ(m.block_names.size(), 2u);
  EXPECT_EQ(m.block_names[0], "gas");
  EXPECT_EQ(m.block_names[1], "steel");
  EXPECT_EQ(m.element_block, (std::vector<int>{0, 1}));
  ASSERT_EQ(m.face_sets.at("bottom").size(), 2u);
  EXPECT_EQ(m.node_sets.at("bottom").size(), 3u);
  // The left face belongs to element 0 and is ordered outward: normal -x.
  const auto& f = m.face_sets.at("left").at(0);
  EXPECT_EQ(f.element, 0);
  const double* a = &m.x0[2 * f.nodes[0]];
  const double* b = &m.x0[2 * f.nodes[1]];
  EXPECT_LT(b[1] - a[1], 0.0);  // n = (dy, -dx) points to -x
  EXPECT_EQ(b[0] - a[0], 0.0);
}

// A scene on the file mesh: blocks by group name (in any order), symmetry and pressure on file sets.
TEST(SolidGmsh, SceneRunsOnFileMesh) {
  SolidScene s = parse_solid_scene(fmt::format(R"(
solid:
  mesh: {{type: gmsh, file: {}}}
  blocks:
    - {{name: steel, material: steel}}
    - {{name: gas, eos: {{type: ideal_gas, gamma: 1.4}}, density: 1.0, initial: {{pressure: 1.0e5}}}}
  boundaries:
    - {{set: bottom, type: symmetry}}
    - {{set: left, type: symmetry}}
    - {{set: right, type: pressure, value: 1.0e5}}
  time: {{end: 1.0e-6}}
)",
                                               kData + "two_blocks_2d.msh"));
  EXPECT_EQ(s.dim, 2);
  Simulation sim(s);
  EXPECT_EQ(sim.mesh().block_names[0], "steel");
  EXPECT_NEAR(sim.state().emass[sim.mesh().block_range[0][0]], 7810.0, 1e-9);
  solid_test::run_to(sim, 1e-6);
  const auto e = sim.energy();
  EXPECT_NEAR(e.total() - e.boundary_work, 2.5e5, 1e-9 * 2.5e5);  // gas: p V / (gamma - 1) = 2.5e5 J
  // A scene block that names no group of the file, and a group without a block.
  auto err = [](const std::string& yaml) {
    try {
      parse_solid_scene(yaml);
    } catch (const cosim::config::ConfigError& ex) { return std::string(ex.what()); }
    return std::string();
  };
  const std::string yaml = fmt::format(R"(
solid:
  mesh: {{type: gmsh, file: {}}}
  blocks:
    - {{name: gass, eos: {{type: ideal_gas, gamma: 1.4}}, density: 1.0}}
    - {{name: steel, material: steel}}
  time: {{end: 1.0}}
)",
                                       kData + "two_blocks_2d.msh");
  const std::string e1 = err(yaml);
  EXPECT_NE(e1.find("'gass'"), std::string::npos) << e1;
  EXPECT_NE(e1.find("gas, steel"), std::string::npos) << e1;
  EXPECT_NE(e1.find("<scene>:5"), std::string::npos) << e1;
  const std::string e2 =
      err(replace(yaml, "    - {name: gass, eos: {type: ideal_gas, gamma: 1.4}, density: 1.0}\n", ""));
  EXPECT_NE(e2.find("group 'gas' has none"), std::string::npos) << e2;
  const std::string e3 = err(replace(yaml, "two_blocks_2d.msh", "no_such_file.msh"));
  EXPECT_NE(e3.find("cannot open"), std::string::npos) << e3;
  EXPECT_NE(e3.find("solid.mesh.file"), std::string::npos) << e3;
}

TEST(SolidGmsh, Reads3DHexStrip) {
  const std::string path = write_tmp("strip.msh", hex_strip(3));
  const Mesh m = read_gmsh(path);
  EXPECT_EQ(m.dim, 3);
  EXPECT_EQ(m.num_elements, 3);
  EXPECT_EQ(m.num_nodes, 16);
  ASSERT_EQ(m.face_sets.at("x_max").size(), 1u);
  EXPECT_EQ(m.face_sets.at("x_max")[0].element, 2);
  EXPECT_EQ(m.node_sets.at("x_min").size(), 4u);
  double an[3];
  Mesh mm = m;
  finalize_mesh(mm);
  face_area_vector(3, mm.x0.data(), mm.face_sets.at("x_max")[0].nodes, an);
  EXPECT_NEAR(an[0], 1.0, 1e-14);  // outward (+x), unit area
}

TEST(SolidGmsh, BadFilesNameElementGroupAndLine) {
  const std::string good = read_text(kData + "two_blocks_2d.msh");
  // Element line "5 1 2 5 4" is line 46 of the file, the left boundary line "1 1 4" line 39.
  const std::string inv = error_of(write_tmp("inv.msh", replace(good, "5 1 2 5 4", "5 1 4 5 2")));
  EXPECT_NE(inv.find("solid_gmsh_inv.msh:46: element 5 of group 'gas': inverted"), std::string::npos) << inv;
  const std::string deg = error_of(write_tmp("deg.msh", replace(good, "5 1 2 5 4", "5 1 2 2 4")));
  EXPECT_NE(deg.find(":46: element 5 of group 'gas': degenerate"), std::string::npos) << deg;
  const std::string bow = error_of(write_tmp("bow.msh", replace(good, "5 1 2 5 4", "5 1 2 4 5")));
  EXPECT_NE(bow.find("element 5 of group 'gas': inverted or self-intersecting"), std::string::npos) << bow;
  const std::string tri = error_of(write_tmp("tri.msh", replace(good, "2 1 3 1\n5 1 2 5 4", "2 1 2 1\n5 1 2 5")));
  EXPECT_NE(tri.find(":46: element 5: element type 2 (3-node triangle) is not supported"), std::string::npos) << tri;
  const std::string nogroup =
      error_of(write_tmp("nogroup.msh", replace(good, "1 0 0 0 1 1 0 1 21 0", "1 0 0 0 1 1 0 0 0")));
  EXPECT_NE(nogroup.find(":46: element 5 (surface 1) belongs to no physical group"), std::string::npos) << nogroup;
  const std::string notface = error_of(write_tmp("notface.msh", replace(good, "1 1 4\n", "1 1 5\n")));
  EXPECT_NE(notface.find(":39: boundary element 1 of group 'left' is not a face"), std::string::npos) << notface;
  const std::string ver = error_of(write_tmp("ver.msh", replace(good, "4.1 0 8", "2.2 0 8")));
  EXPECT_NE(ver.find(":2: MSH format version 2.2 is not supported"), std::string::npos) << ver;
  const std::string trunc = error_of(write_tmp("trunc.msh", good.substr(0, good.find("$EndNodes"))));
  EXPECT_NE(trunc.find("expected"), std::string::npos) << trunc;
  // Corrupt counts: never a huge allocation or a crash, a message with the line (was std::bad_alloc, exit 134).
  const std::size_t nodes_at = good.find("$Nodes\n") + 7;
  const std::string header = good.substr(nodes_at, good.find('\n', nodes_at) - nodes_at);  // "blocks nodes min max"
  std::istringstream hs(header);
  long blocks = 0, nodes = 0;
  hs >> blocks >> nodes;
  for (const char* count : {"999999999999", "-5"}) {
    const std::string bad = replace(good, header, fmt::format("{} {} 1 {}", blocks, count, nodes));
    const std::string e = error_of(write_tmp("count.msh", bad));
    EXPECT_NE(e.find("solid_gmsh_count.msh:"), std::string::npos) << e;
    EXPECT_NE(e.find(std::string("numNodes is ") + count), std::string::npos) << e;
  }
  // 3D: a left-handed hexahedron (top and bottom swapped).
  const std::string hex = error_of(
      write_tmp("hex.msh", hex_strip(2, [](auto& h) { std::rotate(h[1].begin(), h[1].begin() + 4, h[1].end()); })));
  EXPECT_NE(hex.find("element 4 of group 'body': inverted (negative volume at every corner"), std::string::npos) << hex;
}

// Declared counts are checked against what the blocks hold, each error at the header's or block's line: $Elements'
// numElements (it was not read at all: 10 or 9e18 passed), numEntityBlocks of both sections, $Nodes' numNodes; a
// count like 9e18 is never used to allocate.
TEST(SolidGmsh, DeclaredCountsMatchTheBlocks) {
  const std::string good = read_text(kData + "two_blocks_2d.msh");
  // "$Elements" header at line 37 ("5 6 1 6": 5 blocks, 6 elements), its blocks at 38, 40, 42, 45, 47; "$Nodes"
  // header at line 21 ("1 6 1 6"), its block at 22.
  struct Case {
    std::string from, to, expected;
  };
  for (const Case& c : std::vector<Case>{
           {"$Elements\n5 6 1 6", "$Elements\n5 10 1 6",
            ":37: numElements is 10, but the element blocks hold 6 elements"},
           {"$Elements\n5 6 1 6", "$Elements\n5 9000000000000000000 1 6",
            ":37: numElements is 9000000000000000000, but only 12 lines follow in the file"},
           {"$Elements\n5 6 1 6", "$Elements\n5 9e18 1 6", ":37: numElements is '9e18': expected a whole number"},
           {"$Elements\n5 6 1 6", "$Elements\n5 99999999999999999999 1 6",
            ":37: numElements is 99999999999999999999: far more than any mesh holds"},
           {"$Elements\n5 6 1 6", "$Elements\n5 4 1 6",
            ":45: the element blocks hold more elements than the 4 the $Elements header (line 37) declares"},
           {"$Elements\n5 6 1 6", "$Elements\n6 6 1 6",
            ":49: the $Elements section declares numEntityBlocks = 6, but ends after 5 block(s)"},
           {"$Elements\n5 6 1 6", "$Elements\n4 6 1 6",
            ":47: expected $EndElements after the 4 element block(s) numEntityBlocks declares: the section holds "
            "more than it declares"},
           {"$Nodes\n1 6 1 6", "$Nodes\n1 7 1 6", ":21: numNodes is 7, but the node blocks hold 6 nodes"},
           {"$Nodes\n1 6 1 6", "$Nodes\n1 5 1 6",
            ":22: the node blocks hold more nodes than the 5 the $Nodes header (line 21) declares"},
           {"$Nodes\n1 6 1 6", "$Nodes\n2 6 1 6",
            ":35: the $Nodes section declares numEntityBlocks = 2, but ends after 1 block(s)"}}) {
    const std::string e = error_of(write_tmp("counts.msh", replace(good, c.from, c.to)));
    EXPECT_NE(e.find("solid_gmsh_counts.msh" + c.expected), std::string::npos) << c.to << ": " << e;
  }
}

// A directory given as the mesh file is named as one (it said "no $MeshFormat section").
TEST(SolidGmsh, DirectoryIsNotAMeshFile) {
  const fs::path dir = fs::temp_directory_path() / "solid_gmsh_dir.msh";
  fs::create_directories(dir);
  const std::string e = error_of(dir.string());
  EXPECT_NE(e.find(dir.string() + ": is a directory, not a Gmsh mesh file"), std::string::npos) << e;
  fs::remove_all(dir);
}

// A coordinate that is not finite or beyond 1e100 m is refused at its line (1e308 was reported later as a degenerate
// element: the corner Jacobians overflowed).
TEST(SolidGmsh, AbsurdCoordinateIsRefusedAtItsLine) {
  const std::string good = read_text(kData + "two_blocks_2d.msh");
  for (const char* x : {"1e308", "-1e101"}) {
    const std::string e =
        error_of(write_tmp("coord.msh", replace(good, "2 1 0\n$EndNodes", std::string(x) + " 1 0\n$EndNodes")));
    EXPECT_NE(e.find(fmt::format("solid_gmsh_coord.msh:34: node 6: coordinate {:g} is not a finite number of at most "
                                 "1e100 m in magnitude",
                                 std::stod(x))),
              std::string::npos)
        << x << ": " << e;
  }
  for (const char* x : {"inf", "nan"}) {
    const std::string e =
        error_of(write_tmp("coord.msh", replace(good, "2 1 0\n$EndNodes", std::string(x) + " 1 0\n$EndNodes")));
    EXPECT_NE(e.find("solid_gmsh_coord.msh:34: "), std::string::npos) << x << ": " << e;
  }
  EXPECT_EQ(error_of(write_tmp("coord.msh", replace(good, "2 1 0\n$EndNodes", "2 1e99 0\n$EndNodes"))).find("node 6"),
            std::string::npos);
}

// A physical group name that is not printable UTF-8 (invalid bytes, control characters) is refused at its line with
// the bytes escaped: it used to be echoed raw, and offered as a "did you mean" suggestion by the scene. Printable
// UTF-8 names are kept.
TEST(SolidGmsh, GroupNameThatIsNotPrintableUtf8IsRefusedEscaped) {
  const std::string good = read_text(kData + "two_blocks_2d.msh");
  for (const auto& [name, shown] :
       std::vector<std::pair<std::string, std::string>>{{"g\xff\xfe"
                                                         "as",
                                                         "g\\xff\\xfeas"},
                                                        {"gas\x1b[2J", "gas\\x1b[2J"},
                                                        {"\xc0\xaf", "\\xc0\\xaf"}}) {  // an overlong '/'
    const std::string e = error_of(write_tmp("name.msh", replace(good, "\"gas\"", "\"" + name + "\"")));
    EXPECT_NE(
        e.find("solid_gmsh_name.msh:9: physical group 21 is named '" + shown + "', which is not printable UTF-8 text"),
        std::string::npos)
        << e;
    EXPECT_EQ(e.find(name), std::string::npos) << e;
  }
  const Mesh m = read_gmsh(write_tmp("name.msh", replace(good, "\"gas\"", "\"gas_\xc3\xa9t\xc3\xa9\"")));  // gas_été
  EXPECT_EQ(m.block_names[0], "gas_\xc3\xa9t\xc3\xa9");
  // the scene that names a group of such a file gets the reader's message, not a raw suggestion
  try {
    parse_solid_scene(fmt::format(R"(
solid:
  mesh: {{type: gmsh, file: {}}}
  blocks:
    - {{name: steel, material: steel}}
    - {{name: gas, eos: {{type: ideal_gas, gamma: 1.4}}, density: 1.0}}
  time: {{end: 1.0}}
)",
                                  write_tmp("name.msh", replace(good, "\"gas\"",
                                                                "\"g\xff\xfe"
                                                                "as\""))));
    ADD_FAILURE() << "accepted";
  } catch (const cosim::config::ConfigError& ex) {
    const std::string e = ex.what();
    EXPECT_NE(e.find("'g\\xff\\xfeas'"), std::string::npos) << e;
    EXPECT_EQ(e.find("did you mean"), std::string::npos) << e;
    EXPECT_EQ(e.find("\xff"), std::string::npos) << e;
  }
}
