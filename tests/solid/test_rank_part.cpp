// A rank's share of a partitioned mesh (mesh/rank_part.h): every element owned by one rank, every node by one rank,
// every element touching a rank's nodes computed there, every node of those elements either owned there or received
// from its owner, and the send and receive lists of two ranks matching item for item.
#include <gtest/gtest.h>

#include <algorithm>

#include "solid_solver/mesh/partition.h"
#include "solid_solver/mesh/rank_part.h"

namespace {

using namespace cosim::solid;

void check_parts(const Mesh& m, int ranks) {
  const MeshPartition p = partition_elements(m, ranks);
  std::vector<RankPart> parts;
  for (int r = 0; r < ranks; ++r) parts.push_back(make_rank_part(m, p, r));
  std::vector<int> element_owners(static_cast<std::size_t>(m.num_elements), 0);
  std::vector<int> node_owners(static_cast<std::size_t>(m.num_nodes), 0);
  for (const RankPart& rp : parts) {
    for (int e = 0; e < m.num_elements; ++e) element_owners[e] += rp.element_role[e] == kElementOwned;
    for (int n : rp.owned_nodes) ++node_owners[n];
    // Every element touching an owned node is computed here; every node of a computed element is owned here or
    // received.
    std::vector<char> here(static_cast<std::size_t>(m.num_nodes), 0), received(here);
    for (int n : rp.owned_nodes) here[n] = 1;
    for (const auto& list : rp.ghosts.recv)
      for (int n : list) received[n] = 1;
    for (int e = 0; e < m.num_elements; ++e) {
      bool touches = false, complete = true;
      for (int a = 0; a < m.npe; ++a) {
        const int n = m.conn[static_cast<std::size_t>(e) * m.npe + a];
        touches = touches || here[n];
        complete = complete && (here[n] || received[n]);
      }
      EXPECT_TRUE(!touches || rp.element_role[e] != kElementAbsent) << "rank " << rp.rank << " element " << e;
      EXPECT_TRUE(rp.element_role[e] == kElementAbsent || complete) << "rank " << rp.rank << " element " << e;
    }
    // Runs cover exactly the computed elements, in order, within blocks.
    int covered = 0, last = -1;
    for (const RankPart::Run& run : rp.runs) {
      EXPECT_GT(run.begin, last);
      EXPECT_EQ(m.element_block[run.begin], m.element_block[run.end - 1]);
      for (int e = run.begin; e < run.end; ++e) EXPECT_EQ(rp.element_role[e], run.role);
      covered += run.end - run.begin;
      last = run.end - 1;
    }
    EXPECT_EQ(covered, rp.owned_elements + rp.halo_elements);
  }
  for (int c : element_owners) EXPECT_EQ(c, 1);
  for (int c : node_owners) EXPECT_EQ(c, 1);
  // What r receives from s is what s sends to r.
  for (const RankPart& a : parts)
    for (std::size_t i = 0; i < a.ghosts.neighbours.size(); ++i) {
      const RankPart& b = parts[a.ghosts.neighbours[i]];
      const auto at = std::find(b.ghosts.neighbours.begin(), b.ghosts.neighbours.end(), a.rank);
      ASSERT_NE(at, b.ghosts.neighbours.end());
      EXPECT_EQ(a.ghosts.recv[i], b.ghosts.send[static_cast<std::size_t>(at - b.ghosts.neighbours.begin())]);
      EXPECT_EQ(a.ghosts.send[i], b.ghosts.recv[static_cast<std::size_t>(at - b.ghosts.neighbours.begin())]);
    }
  for (const RankPart& rp : parts) EXPECT_EQ(rp.ghosts.neighbours.empty(), ranks == 1) << "rank " << rp.rank;
}

TEST(SolidRankPart, OwnersHalosAndPlansAreConsistent) {
  for (int ranks : {1, 2, 3, 4}) {
    Mesh quad = make_box_mesh(2, {12, 7, 1}, {0, 0, 0}, {1.2, 0.7, 0});
    finalize_mesh(quad);
    check_parts(quad, ranks);
    Mesh hex = make_box_mesh(3, {5, 4, 3}, {0, 0, 0}, {1, 1, 1});
    for (int e = 0; e < hex.num_elements; e += 3) hex.element_block[e] = 1;  // blocks interleaved: many runs
    hex.block_names = {"a", "b"};
    finalize_mesh(hex);
    check_parts(hex, ranks);
    if (ranks == 1) {  // the one-rank shortcut is what a partition of one part gives
      const RankPart a = whole_mesh_part(hex), b = make_rank_part(hex, partition_elements(hex, 1), 0);
      EXPECT_EQ(a.owned_nodes, b.owned_nodes);
      EXPECT_EQ(a.element_role, b.element_role);
      EXPECT_EQ(a.node_owner, b.node_owner);
      EXPECT_EQ(a.runs.size(), b.runs.size());
      EXPECT_TRUE(b.ghosts.neighbours.empty());
    }
  }
}

}  // namespace
