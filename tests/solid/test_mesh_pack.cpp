// The packed mesh that rank 0 broadcasts (mesh/mesh_pack.h): a Gmsh mesh (2D, as read and finalized) and a 3D box
// mesh with its node and face sets come back equal in every field, coordinates bit for bit; a cut or altered buffer
// is refused with what is wrong, never read past its end.
#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "solid_solver/mesh/gmsh_reader.h"
#include "solid_solver/mesh/mesh_pack.h"

using namespace cosim::solid;

namespace {

void expect_same_mesh(const Mesh& a, const Mesh& b) {
  EXPECT_EQ(a.dim, b.dim);
  EXPECT_EQ(a.npe, b.npe);
  EXPECT_EQ(a.num_nodes, b.num_nodes);
  EXPECT_EQ(a.num_elements, b.num_elements);
  ASSERT_EQ(a.x0.size(), b.x0.size());
  EXPECT_EQ(std::memcmp(a.x0.data(), b.x0.data(), a.x0.size() * sizeof(double)), 0) << "coordinates differ";
  EXPECT_EQ(a.conn, b.conn);
  EXPECT_EQ(a.element_block, b.element_block);
  EXPECT_EQ(a.block_names, b.block_names);
  EXPECT_EQ(a.block_range, b.block_range);
  EXPECT_EQ(a.node_sets, b.node_sets);
  ASSERT_EQ(a.face_sets.size(), b.face_sets.size());
  for (const auto& [name, faces] : a.face_sets) {
    ASSERT_TRUE(b.face_sets.count(name)) << name;
    const auto& other = b.face_sets.at(name);
    ASSERT_EQ(faces.size(), other.size()) << name;
    for (std::size_t k = 0; k < faces.size(); ++k) {
      EXPECT_EQ(faces[k].nodes, other[k].nodes) << name << " face " << k;
      EXPECT_EQ(faces[k].element, other[k].element) << name << " face " << k;
    }
  }
  EXPECT_EQ(a.node_corner_offset, b.node_corner_offset);
  EXPECT_EQ(a.node_corners, b.node_corners);
}

std::string error_of(const std::string& buffer) {
  try {
    unpack_mesh(buffer, "test buffer");
  } catch (const MeshError& e) { return e.what(); }
  return "";
}

}  // namespace

TEST(MeshPack, AGmshMeshComesBackEqual) {
  Mesh m = read_gmsh(std::string(COSIM_SOURCE_DIR) + "/configs/meshes/panel_5x25.msh");
  const std::string raw = pack_mesh(m);  // as read (not finalized: no block ranges, no corner lists yet)
  expect_same_mesh(m, unpack_mesh(raw, "raw"));
  finalize_mesh(m);
  ASSERT_FALSE(m.node_corners.empty());
  ASSERT_FALSE(m.face_sets.at("clamp_top").empty());
  expect_same_mesh(m, unpack_mesh(pack_mesh(m), "finalized"));
  // Compact: about the arrays' own bytes (8 per coordinate, 4 per connectivity entry), far less than the text.
  const double arrays = 8.0 * m.x0.size() + 4.0 * (m.conn.size() + m.element_block.size());
  EXPECT_LT(static_cast<double>(raw.size()), 2.5 * arrays) << raw.size();
}

TEST(MeshPack, A3DMeshWithSetsComesBackEqual) {
  Mesh m = make_box_mesh(3, {3, 4, 5}, {0.0, -1.0, 0.5}, {0.3, 1.0 / 3.0, 2.0});
  for (int e = 0; e < m.num_elements; ++e) m.element_block[e] = e % 3 == 0 ? 1 : 0;
  m.block_names = {"steel", "air"};
  finalize_mesh(m);
  ASSERT_EQ(m.face_sets.at("z_upper").size(), 12u);
  expect_same_mesh(m, unpack_mesh(pack_mesh(m), "box"));
}

TEST(MeshPack, ACutOrAlteredBufferIsRefused) {
  Mesh m = make_box_mesh(2, {4, 2, 1}, {0, 0, 0}, {1, 1, 1});
  m.block_names = {"b"};
  finalize_mesh(m);
  const std::string p = pack_mesh(m);
  for (std::size_t cut : {std::size_t{0}, std::size_t{3}, std::size_t{40}, p.size() / 2, p.size() - 1})
    EXPECT_NE(error_of(p.substr(0, cut)).find("test buffer: not a packed mesh (it ends early"), std::string::npos)
        << cut << ": " << error_of(p.substr(0, cut));
  EXPECT_NE(error_of(p + "x").find("bytes left over"), std::string::npos);
  std::string tag = p;
  tag[0] = 'X';
  EXPECT_NE(error_of(tag).find("another layout tag"), std::string::npos);
  std::string count = p;  // the element count (after the tag, dim, npe, nodes) one too many
  int ne = 0;
  std::memcpy(&ne, count.data() + 4 + 3 * sizeof(int), sizeof ne);
  ++ne;
  std::memcpy(count.data() + 4 + 3 * sizeof(int), &ne, sizeof ne);
  EXPECT_NE(error_of(count).find("arrays of other lengths than the counts"), std::string::npos) << error_of(count);
}
