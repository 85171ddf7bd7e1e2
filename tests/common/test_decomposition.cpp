// The Cartesian decomposition of the fluid mesh (common/parallel/decomposition.h): the layout with the least cut
// area, refused where blocks would be thinner than the stencil's reach, and blocks that cover the mesh exactly once
// with the owner of every cell found again.
#include <gtest/gtest.h>

#include <vector>

#include "common/parallel/decomposition.h"

using namespace cosim::parallel;

TEST(Decomposition, TheLayoutCutsTheLeastAreaAndOrdersTiesLikeMpiDimsCreate) {
  EXPECT_EQ(choose_layout(1, 3, {10, 10, 10}, 3).blocks, (Index3{1, 1, 1}));
  EXPECT_EQ(choose_layout(4, 2, {1000, 1000, 1}, 3).blocks, (Index3{2, 2, 1}));
  EXPECT_EQ(choose_layout(4, 2, {1000, 10, 1}, 3).blocks, (Index3{4, 1, 1}));  // a long tube: cuts across it
  EXPECT_EQ(choose_layout(4, 2, {10, 1000, 1}, 3).blocks, (Index3{1, 4, 1}));
  EXPECT_EQ(choose_layout(8, 3, {128, 128, 128}, 3).blocks, (Index3{2, 2, 2}));
  EXPECT_EQ(choose_layout(6, 3, {100, 100, 100}, 3).blocks, (Index3{1, 2, 3}));  // ties: the slow axes split
  EXPECT_EQ(choose_layout(7, 2, {1000, 1000, 1}, 3).blocks, (Index3{1, 7, 1}));
  EXPECT_EQ(choose_layout(2, 3, {128, 128, 128}, 3).blocks, (Index3{1, 1, 2}));
  EXPECT_EQ(choose_layout(3, 1, {800, 1, 1}, 3).blocks, (Index3{3, 1, 1}));
  const Layout big = choose_layout(4096, 3, {1000, 1000, 1000}, 3);
  EXPECT_EQ(big.blocks, (Index3{16, 16, 16}));
  // A mesh too small along the axis it would have to split: the next best layout, or a refusal saying why.
  EXPECT_EQ(choose_layout(4, 2, {8, 1000, 1}, 5).blocks, (Index3{1, 4, 1}));  // 2 x 2 would leave 4 cells along x
  try {
    choose_layout(64, 1, {100, 1, 1}, 3);
    FAIL() << "64 blocks of 1-2 cells accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(
        std::string(e.what()).find("64 ranks cannot share a 1D mesh of 100 x 1 x 1 cells in blocks of at least 3"),
        std::string::npos)
        << e.what();
  }
}

TEST(Decomposition, AGivenLayoutIsCheckedAgainstTheRanksAndTheMesh) {
  EXPECT_FALSE(layout_problem({{2, 2, 1}}, 4, 2, {100, 100, 1}, 3));
  EXPECT_EQ(*layout_problem({{2, 3, 1}}, 4, 2, {100, 100, 1}, 3), "2 x 3 x 1 blocks make 6 ranks, but the run has 4");
  EXPECT_EQ(*layout_problem({{1, 1, 2}}, 2, 2, {100, 100, 1}, 3), "2 blocks along z, but the mesh is 2D");
  EXPECT_EQ(*layout_problem({{4, 1, 1}}, 4, 2, {10, 100, 1}, 3),
            "10 cells along x cannot be split into 4 blocks of at least 3 cells (the stencil's reach)");
  EXPECT_EQ(*layout_problem({{0, 1, 1}}, 0, 2, {10, 100, 1}, 3), "0 blocks along x: at least 1 expected");
}

TEST(Decomposition, BlocksCoverTheMeshOnceEvenlyAndEveryCellsOwnerIsItsBlock) {
  for (const auto& [ranks, dim, cells] : std::vector<std::tuple<int, int, Index3>>{
           {1, 1, {17, 1, 1}}, {3, 1, {800, 1, 1}}, {4, 2, {50, 37, 1}}, {6, 3, {13, 11, 9}}, {12, 3, {40, 30, 20}}}) {
    const Layout l = choose_layout(ranks, dim, cells, 3);
    std::vector<int> owner(static_cast<std::size_t>(cells[0] * cells[1] * cells[2]), -1);
    long total = 0;
    for (int r = 0; r < ranks; ++r) {
      const Block b = block_of(l, r, cells);
      EXPECT_EQ(b.rank, r);
      total += b.cells();
      for (int d = 0; d < 3; ++d) {
        // Even: the blocks along an axis differ by one cell at most.
        const int n = b.upper[d] - b.lower[d];
        EXPECT_LE(std::abs(n - cells[d] / l.blocks[d]), 1) << "rank " << r << " axis " << d;
      }
      for (int i = b.lower[0]; i < b.upper[0]; ++i)
        for (int j = b.lower[1]; j < b.upper[1]; ++j)
          for (int k = b.lower[2]; k < b.upper[2]; ++k) {
            int& o = owner[static_cast<std::size_t>((i * cells[1] + j) * cells[2] + k)];
            EXPECT_EQ(o, -1) << "cell in two blocks";
            o = r;
            ASSERT_EQ(owner_of(l, {i, j, k}, cells), r) << i << " " << j << " " << k;
          }
    }
    EXPECT_EQ(total, long(cells[0]) * cells[1] * cells[2]);
    for (int o : owner) ASSERT_GE(o, 0) << "a cell in no block";
  }
}

TEST(Decomposition, SplitGivesTheFirstPartsTheRemainder) {
  EXPECT_EQ(split(10, 3, 0), (std::array<int, 2>{0, 4}));
  EXPECT_EQ(split(10, 3, 1), (std::array<int, 2>{4, 7}));
  EXPECT_EQ(split(10, 3, 2), (std::array<int, 2>{7, 10}));
  EXPECT_EQ(split(9, 3, 2), (std::array<int, 2>{6, 9}));
}
