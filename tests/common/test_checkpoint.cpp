// Tests for common/checkpoint: part files (round trip, length checks, a part is whole or absent), checkpoint sets
// (complete only with every part and the manifest, newest chosen, pruning), when a set is due, and the outputs a
// restart continues (tables cut back to the checkpoint, snapshot series resumed).
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "common/checkpoint/checkpoint_sets.h"
#include "common/checkpoint/output_resume.h"
#include "common/checkpoint/part_file.h"
#include "tests/support/scratch_dir.h"

namespace fs = std::filesystem;
using namespace cosim::checkpoint;

namespace {
std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_set(const fs::path& root, long cycle, bool complete) {
  const fs::path dir = prepare_set(root, cycle);
  for (const char* kind : {"coupler", "fluid"}) {
    PartWriter w(dir / (std::string(kind) + ".h5"), kind);
    w.put_integer("cycle", cycle);
    w.commit();
  }
  if (complete) write_manifest(dir, cycle, 0.1 * cycle, {{"parts", {"coupler.h5", "fluid.h5"}}});
}
}  // namespace

TEST(CheckpointPart, RoundTripsEveryKindOfEntryBitForBit) {
  const fs::path dir = cosim::test::scratch_path("ck_part");
  fs::create_directories(dir);
  const std::vector<double> x = {1.0 / 3.0, -0.0, 1e-310, 6.02e23};
  const std::vector<std::int64_t> n = {-5, 0, 1LL << 40};
  const std::vector<std::uint8_t> b = {0, 7, 255};
  {
    PartWriter w(dir / "fluid.h5", "fluid");
    w.put("x", x);
    w.put("n", n);
    w.put("b", b);
    w.put("empty", std::vector<double>{});
    w.put_text("text", std::string("a\x1e<Grid/>\n", 10));
    w.put_scalar("time", 0.1 + 0.2);
    w.put_integer("cycle", 12345);
    EXPECT_FALSE(fs::exists(dir / "fluid.h5")) << "visible before it is complete";
    w.commit();
  }
  const PartReader r(dir / "fluid.h5", "fluid");
  EXPECT_EQ(r.doubles("x", 4), x);
  EXPECT_EQ(r.integers("n"), n);
  EXPECT_EQ(r.bytes("b"), b);
  EXPECT_TRUE(r.doubles("empty").empty());
  EXPECT_EQ(r.text("text"), std::string("a\x1e<Grid/>\n", 10));
  EXPECT_EQ(r.scalar("time"), 0.1 + 0.2);
  EXPECT_EQ(r.integer("cycle"), 12345);
  // A part of another mesh: the length is named.
  try {
    r.doubles("x", 5);
    FAIL() << "a wrong length was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("'x' holds 4 values, this run needs 5"), std::string::npos) << e.what();
  }
  // Another process's part, and a file that is not a part, are refused by name.
  EXPECT_THROW(PartReader(dir / "fluid.h5", "solid"), std::runtime_error);
  std::ofstream(dir / "junk.h5") << "not hdf5";
  EXPECT_THROW(PartReader(dir / "junk.h5", "fluid"), std::runtime_error);
  EXPECT_THROW(PartReader(dir / "missing.h5", "fluid"), std::runtime_error);
}

TEST(CheckpointPart, AnUncommittedPartLeavesNothing) {
  const fs::path dir = cosim::test::scratch_path("ck_uncommitted");
  fs::create_directories(dir);
  {
    PartWriter w(dir / "solid.h5", "solid");
    w.put("x", std::vector<double>(1000, 1.0));
  }  // a writer that fails before commit (an exception) is discarded
  EXPECT_TRUE(fs::is_empty(dir));
}

TEST(CheckpointSets, OnlyCompleteSetsCountAndTheNewestIsChosen) {
  const fs::path root = cosim::test::scratch_path("ck_sets");
  EXPECT_THROW(find_set(root), std::runtime_error);  // none written
  write_set(root, 100, true);
  write_set(root, 200, true);
  write_set(root, 300, false);  // no manifest: a process did not confirm
  const auto sets = complete_sets(root);
  ASSERT_EQ(sets.size(), 2u);
  EXPECT_EQ(sets[0].cycle, 100);
  EXPECT_EQ(find_set(root).cycle, 200);
  EXPECT_DOUBLE_EQ(find_set(root).time, 20.0);
  EXPECT_EQ(find_set(root, 100).cycle, 100);
  EXPECT_THROW(find_set(root, 300), std::runtime_error);
  // A part named by the manifest but gone: incomplete.
  fs::remove(set_path(root, 200) / "fluid.h5");
  EXPECT_EQ(find_set(root).cycle, 100);
  try {
    find_set(root, 200);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("fluid.h5, which is missing"), std::string::npos) << e.what();
  }
  // A manifest cannot be written for a set with a part missing.
  EXPECT_THROW(write_manifest(set_path(root, 300), 300, 30, {{"parts", {"coupler.h5", "solid.h5"}}}),
               std::runtime_error);
}

TEST(CheckpointSets, PruneKeepsTheNewestCompleteSetsAndDropsOlderIncompleteOnes) {
  const fs::path root = cosim::test::scratch_path("ck_prune");
  write_set(root, 1, true);
  write_set(root, 2, false);
  write_set(root, 3, true);
  write_set(root, 4, true);
  write_set(root, 5, false);  // being written: newer than every complete set, kept
  prune(root, 2);
  EXPECT_FALSE(fs::exists(set_path(root, 1)));
  EXPECT_FALSE(fs::exists(set_path(root, 2)));
  EXPECT_TRUE(fs::exists(set_path(root, 3)));
  EXPECT_TRUE(fs::exists(set_path(root, 4)));
  EXPECT_TRUE(fs::exists(set_path(root, 5)));
  std::ofstream(root / "notes.txt") << "the user's";
  clear(root);
  EXPECT_TRUE(complete_sets(root).empty());
  EXPECT_FALSE(fs::exists(set_path(root, 5)));
  EXPECT_TRUE(fs::exists(root / "notes.txt")) << "clear removes the sets only";
}

TEST(CheckpointPolicy, DueWhenTheIntervalIsCrossedOrTheCycleCountReached) {
  CheckpointPolicy p;
  p.interval = 0.1;
  EXPECT_FALSE(p.due(1, 0.0, 0.05));
  EXPECT_TRUE(p.due(2, 0.05, 0.1));  // lands on the multiple
  EXPECT_FALSE(p.due(3, 0.1, 0.15));
  EXPECT_TRUE(p.due(4, 0.15, 0.31));  // crosses two: one set
  CheckpointPolicy c;
  c.cycles = 50;
  EXPECT_FALSE(c.due(49, 0, 1));
  EXPECT_TRUE(c.due(100, 0, 1));
  EXPECT_FALSE(CheckpointPolicy{}.enabled());
}

TEST(CheckpointOutputs, ATableIsCutBackToTheCheckpointAndContinues) {
  const fs::path dir = cosim::test::scratch_path("ck_table");
  fs::create_directories(dir);
  const fs::path file = dir / "h.csv";
  {
    cosim::io::LineLog log(file, "a,b\n");
    log.append("1,2\n");
    PartWriter w(dir / "coupler.h5", "coupler");
    put_log(w, "h", log);
    w.commit();
    log.append("3,4\n");  // after the checkpoint: the run that stopped
  }
  {
    cosim::io::LineLog log = resume_log(PartReader(dir / "coupler.h5", "coupler"), "h", file);
    log.append("5,6\n");
  }
  EXPECT_EQ(slurp(file), "a,b\n1,2\n5,6\n");
  // A table shorter than the checkpoint says it: it is not the same run's.
  std::ofstream(file, std::ios::trunc) << "a\n";
  EXPECT_THROW(resume_log(PartReader(dir / "coupler.h5", "coupler"), "h", file), std::runtime_error);
}

TEST(CheckpointOutputs, ASnapshotSeriesContinuesAfterItsCheckpointedEntries) {
  const fs::path dir = cosim::test::scratch_path("ck_series");
  fs::create_directories(dir);
  const std::vector<double> rho = {1, 2};
  const cosim::io::UniformGrid g{1, {2, 1, 1}, {0, 0, 0}, {0.5, 1, 1}};
  const auto write = [&](cosim::io::SnapshotSeries& s, double t) {
    s.write(t, 0, g, {{"rho", rho.data(), 1, cosim::io::Center::Cell}});
  };
  {
    cosim::io::SnapshotSeries s(dir, "f");
    write(s, 0.0);
    write(s, 1.0);
    PartWriter w(dir / "fluid.h5", "fluid");
    put_series(w, "f", s);
    w.commit();
    write(s, 2.0);  // after the checkpoint
    write(s, 3.0);
  }
  const std::string index_at_2 = [&] {
    cosim::io::SnapshotSeries s(dir / "ref", "f");
    fs::create_directories(dir / "ref");
    write(s, 0.0);
    write(s, 1.0);
    write(s, 2.5);
    return slurp(dir / "ref" / "f.xmf");
  }();
  cosim::io::SnapshotSeries s(dir, "f");
  resume_series(PartReader(dir / "fluid.h5", "fluid"), "f", s);
  EXPECT_EQ(s.count(), 2u);
  EXPECT_TRUE(fs::exists(dir / "f_000001.h5"));
  EXPECT_FALSE(fs::exists(dir / "f_000002.h5")) << "a snapshot after the checkpoint was kept";
  EXPECT_FALSE(fs::exists(dir / "f_000003.h5"));
  write(s, 2.5);
  EXPECT_EQ(slurp(dir / "f.xmf"), index_at_2) << "the index is not the one of an uninterrupted series";
  // A kept snapshot that is gone: the series cannot continue.
  fs::remove(dir / "f_000000.h5");
  cosim::io::SnapshotSeries again(dir, "f");
  EXPECT_THROW(resume_series(PartReader(dir / "fluid.h5", "fluid"), "f", again), std::runtime_error);
}
