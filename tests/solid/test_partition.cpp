// The solid mesh split over ranks by METIS: every element in one part, parts of equal size, each part connected,
// the cut near the least a straight cut gives, the same answer every time, owners and shared nodes consistent.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <queue>

#include "solid_solver/mesh/element_faces.h"
#include "solid_solver/mesh/partition.h"

namespace {

using cosim::solid::Mesh;
using cosim::solid::MeshPartition;

// Whether the elements of `part` form one piece through shared faces.
bool connected(const Mesh& m, const MeshPartition& p, int part) {
  const auto faces = cosim::solid::all_element_faces(m);
  std::vector<std::vector<int>> next(static_cast<std::size_t>(m.num_elements));
  for (std::size_t i = 0; i + 1 < faces.size(); ++i)
    if (faces[i].key == faces[i + 1].key) {
      next[static_cast<std::size_t>(faces[i].element)].push_back(faces[i + 1].element);
      next[static_cast<std::size_t>(faces[i + 1].element)].push_back(faces[i].element);
    }
  std::vector<char> seen(static_cast<std::size_t>(m.num_elements), 0);
  int start = -1, total = 0;
  for (int e = 0; e < m.num_elements; ++e)
    if (p.element_part[static_cast<std::size_t>(e)] == part) {
      ++total;
      if (start < 0) start = e;
    }
  if (start < 0) return false;
  std::queue<int> q;
  q.push(start);
  seen[static_cast<std::size_t>(start)] = 1;
  int reached = 0;
  while (!q.empty()) {
    const int e = q.front();
    q.pop();
    ++reached;
    for (const int f : next[static_cast<std::size_t>(e)])
      if (!seen[static_cast<std::size_t>(f)] && p.element_part[static_cast<std::size_t>(f)] == part) {
        seen[static_cast<std::size_t>(f)] = 1;
        q.push(f);
      }
  }
  return reached == total;
}

void check(const Mesh& m, int parts, long straight_cut) {
  const MeshPartition p = cosim::solid::partition_elements(m, parts);
  ASSERT_EQ(p.element_part.size(), static_cast<std::size_t>(m.num_elements));
  const std::vector<int> sizes = p.elements_per_part();
  const double mean = static_cast<double>(m.num_elements) / parts;
  for (int k = 0; k < parts; ++k) {
    EXPECT_GT(sizes[static_cast<std::size_t>(k)], 0) << parts << " parts";
    EXPECT_LE(sizes[static_cast<std::size_t>(k)], 1.05 * mean + 1) << "part " << k << " of " << parts;
    EXPECT_TRUE(connected(m, p, k)) << "part " << k << " of " << parts << " is in pieces";
  }
  if (parts > 1) {
    EXPECT_LE(p.cut_faces, 1.6 * straight_cut) << parts << " parts";
  }
  EXPECT_EQ(cosim::solid::partition_elements(m, parts).element_part, p.element_part) << "not deterministic";
  // Each node's owner holds one of its elements; a node is shared exactly when its elements are in several parts.
  std::vector<std::vector<int>> parts_of(static_cast<std::size_t>(m.num_nodes));
  for (int e = 0; e < m.num_elements; ++e)
    for (int k = 0; k < m.npe; ++k) {
      auto& l = parts_of[static_cast<std::size_t>(m.conn[static_cast<std::size_t>(e) * m.npe + k])];
      const int part = p.element_part[static_cast<std::size_t>(e)];
      if (std::find(l.begin(), l.end(), part) == l.end()) l.push_back(part);
    }
  for (int n = 0; n < m.num_nodes; ++n) {
    const auto& l = parts_of[static_cast<std::size_t>(n)];
    EXPECT_EQ(p.node_owner[static_cast<std::size_t>(n)], *std::min_element(l.begin(), l.end()));
    for (const int part : l) {
      const auto& shared = p.shared_nodes[static_cast<std::size_t>(part)];
      EXPECT_EQ(std::binary_search(shared.begin(), shared.end(), n), l.size() > 1) << "node " << n;
    }
  }
  std::printf("[ measured ] %d elements in %d parts: sizes %d..%d, %ld cut faces (a straight cut: %ld)\n",
              m.num_elements, parts, *std::min_element(sizes.begin(), sizes.end()),
              *std::max_element(sizes.begin(), sizes.end()), p.cut_faces, straight_cut);
}

TEST(MeshPartition, QuadsSplitIntoConnectedPartsOfEqualSize) {
  const Mesh m = cosim::solid::make_box_mesh(2, {40, 20, 1}, {0, 0, 0}, {2, 1, 1});
  const MeshPartition one = cosim::solid::partition_elements(m, 1);
  EXPECT_EQ(std::count(one.element_part.begin(), one.element_part.end(), 0), m.num_elements);
  EXPECT_EQ(one.cut_faces, 0);
  check(m, 2, 20);      // one cut across the long side
  check(m, 3, 2 * 20);  // two cuts across
  check(m, 4, 3 * 20);
  check(m, 7, 6 * 20);
}

TEST(MeshPartition, HexahedraSplitIntoConnectedPartsOfEqualSize) {
  const Mesh m = cosim::solid::make_box_mesh(3, {16, 10, 8}, {0, 0, 0}, {1.6, 1, 0.8});
  check(m, 2, 10 * 8);
  check(m, 3, 2 * 10 * 8);
  check(m, 4, 3 * 10 * 8);
}

TEST(MeshPartition, MorePartsThanElementsIsRefused) {
  const Mesh m = cosim::solid::make_box_mesh(2, {2, 2, 1}, {0, 0, 0}, {1, 1, 1});
  EXPECT_THROW(cosim::solid::partition_elements(m, 5), std::invalid_argument);
  EXPECT_THROW(cosim::solid::partition_elements(m, 0), std::invalid_argument);
}

}  // namespace
