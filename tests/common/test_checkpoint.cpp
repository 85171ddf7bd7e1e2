// Tests for common/checkpoint: part files (round trip, length checks, a part is whole or absent), checkpoint sets
// (complete only with every part and the manifest, newest chosen, pruning), their integrity (SHA-256 against the
// standard's vectors and sha256sum, a flipped bit, a truncated part, an edited or missing manifest, a part of
// another cycle), when a set is due, and the outputs a restart continues (tables cut back to the checkpoint,
// snapshot series resumed).
#include <gtest/gtest.h>

#include <fstream>
#include <functional>
#include <sstream>

#include "common/checkpoint/checkpoint_sets.h"
#include "common/checkpoint/output_resume.h"
#include "common/checkpoint/part_file.h"
#include "common/util/sha256.h"
#include "tests/support/flip_bit.h"
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

TEST(CheckpointPart, AShapedArrayIsReadBackByPartsAndAnUnshapedOneTheSame) {
  // A 2 x 3 x 4 x 5 array (variables, z, y, x) as the blocks of a split mesh write it, and the same values as one
  // axis (a part from before arrays had shapes): every block reads the same values from either.
  const cosim::io::Hdf5Shape shape{2, 3, 4, 5};
  std::vector<double> all(2 * 3 * 4 * 5);
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = 0.5 * static_cast<double>(i) - 7.0;
  const fs::path dir = cosim::test::scratch_path("ck_shaped");
  fs::create_directories(dir);
  {
    PartWriter w(dir / "shaped.h5", "fluid");
    w.put_part("cells", all, shape, {0, 0, 0, 0}, shape);
    w.commit();
    PartWriter flat(dir / "flat.h5", "fluid");
    flat.put("cells", all);
    flat.commit();
  }
  const cosim::io::Hdf5Shape offset{0, 1, 2, 1}, count{2, 2, 2, 3};
  std::vector<double> expected;
  for (std::uint64_t v = 0; v < 2; ++v)
    for (std::uint64_t k = 1; k < 3; ++k)
      for (std::uint64_t j = 2; j < 4; ++j)
        for (std::uint64_t i = 1; i < 4; ++i) expected.push_back(all[((v * 3 + k) * 4 + j) * 5 + i]);
  for (const char* name : {"shaped.h5", "flat.h5"}) {
    const PartReader r(dir / name, "fluid");
    EXPECT_EQ(r.doubles_part("cells", shape, offset, count), expected) << name;
    EXPECT_EQ(r.doubles_part("cells", shape, {0, 0, 0, 0}, shape), all) << name;
  }
  // Another mesh's array is refused with both shapes named; so is a part beyond the array.
  const PartReader r(dir / "shaped.h5", "fluid");
  try {
    r.doubles_part("cells", {2, 3, 5, 4}, {0, 0, 0, 0}, {2, 3, 5, 4});
    ADD_FAILURE() << "another shape was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("2 x 3 x 4 x 5"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("2 x 3 x 5 x 4"), std::string::npos) << e.what();
  }
  EXPECT_THROW(r.doubles_part("cells", shape, {0, 2, 0, 0}, {2, 2, 4, 5}), std::invalid_argument);
  const PartReader flat(dir / "flat.h5", "fluid");
  EXPECT_THROW(flat.doubles_part("cells", {2, 3, 4, 6}, {0, 0, 0, 0}, {2, 3, 4, 6}), std::runtime_error);
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

namespace {
std::string error_of(const std::function<void()>& fn) {
  try {
    fn();
  } catch (const std::exception& e) { return e.what(); }
  return "";
}
}  // namespace

TEST(Sha256, MatchesTheStandardsTestVectorsAndSha256sum) {
  const auto hex = [](const std::string& text) {
    cosim::util::Sha256 h;
    h.update(std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
    return h.hex_digest();
  };
  // FIPS 180-4 examples (NIST CSRC): "abc", the two-block message, the empty string, a million 'a'.
  EXPECT_EQ(hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(hex(std::string(1000000, 'a')), "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
  // Every length around the block and padding boundaries, fed in uneven pieces, against coreutils' sha256sum.
  const fs::path dir = cosim::test::scratch_path("sha256");
  fs::create_directories(dir);
  for (std::size_t n : {1ul, 55ul, 56ul, 63ul, 64ul, 65ul, 119ul, 120ul, 128ul, 1048577ul + 3}) {
    std::string text(n, '\0');
    for (std::size_t i = 0; i < n; ++i) text[i] = static_cast<char>((i * 7919 + n) % 251);
    const fs::path f = dir / std::to_string(n);
    std::ofstream(f, std::ios::binary) << text;
    ASSERT_EQ(std::system(("sha256sum " + f.string() + " > " + f.string() + ".sum").c_str()), 0);
    const std::string expected = slurp(f.string() + ".sum").substr(0, 64);
    EXPECT_EQ(cosim::util::sha256_of_file(f).sha256, expected) << n << " bytes";
    EXPECT_EQ(cosim::util::sha256_of_file(f).bytes, n);
    cosim::util::Sha256 h;
    for (std::size_t at = 0; at < n;) {
      const std::size_t take = std::min<std::size_t>(n - at, 1 + (at * 31) % 97);
      h.update(std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(text.data()) + at, take));
      at += take;
    }
    EXPECT_EQ(h.hex_digest(), expected) << n << " bytes in pieces";
  }
}

TEST(CheckpointIntegrity, TheManifestRecordsEachPartsChecksumAndAFlippedBitIsRefusedByName) {
  const fs::path root = cosim::test::scratch_path("ck_integrity");
  write_set(root, 100, true);
  write_set(root, 200, true);
  const SetInfo s = read_set(set_path(root, 200));
  EXPECT_EQ(s.manifest["format"], "cosim-checkpoint-set-2");
  const fs::path part = set_path(root, 200) / "coupler.h5";
  EXPECT_EQ(s.manifest["checksums"]["coupler.h5"]["sha256"], cosim::util::sha256_of_file(part).sha256);
  EXPECT_EQ(s.manifest["checksums"]["coupler.h5"]["bytes"], fs::file_size(part));
  EXPECT_NO_THROW(verify_set(s));
  EXPECT_NO_THROW(open_verified_part(set_path(root, 200), "fluid.h5", "fluid"));
  // A set named with a trailing separator, as a shell's completion writes it (`--restart .../000000200/`).
  EXPECT_NO_THROW(open_verified_part(set_path(root, 200) / "", "fluid.h5", "fluid"));
  // One bit, in the middle of the data: the part is refused, the newest intact set is chosen and the refusal said.
  cosim::test::flip_bit(part, -100);
  std::string why = error_of([&] { verify_set(read_set(set_path(root, 200))); });
  EXPECT_NE(why.find("coupler.h5: SHA-256"), std::string::npos) << why;
  EXPECT_NE(why.find("the part is corrupt"), std::string::npos) << why;
  why = error_of([&] { open_verified_part(set_path(root, 200), "coupler.h5", "coupler"); });
  EXPECT_NE(why.find("the part is corrupt"), std::string::npos) << why;
  const SetChoice c = choose_set(root);
  EXPECT_EQ(c.set.cycle, 100);
  ASSERT_EQ(c.skipped.size(), 1u);
  EXPECT_NE(c.skipped[0].find("000000200/coupler.h5"), std::string::npos) << c.skipped[0];
  why = error_of([&] { choose_set(root, 200); });  // asked for by number: refused, not replaced
  EXPECT_NE(why.find("the part is corrupt"), std::string::npos) << why;
  // A truncated part.
  fs::resize_file(set_path(root, 100) / "fluid.h5", fs::file_size(set_path(root, 100) / "fluid.h5") - 1);
  why = error_of([&] { choose_set(root); });
  EXPECT_NE(why.find("none complete and intact"), std::string::npos) << why;
  EXPECT_NE(why.find("the part is truncated or replaced"), std::string::npos) << why;
}

TEST(CheckpointIntegrity, AnEditedOrMissingManifestAndAPartOfAnotherCycleAreNamed) {
  const fs::path root = cosim::test::scratch_path("ck_manifest");
  write_set(root, 100, true);
  write_set(root, 200, true);
  write_set(root, 300, true);
  write_set(root, 400, true);
  // The manifest of 400 edited to say 390: the set's directory and its parts say 400.
  {
    nlohmann::json m = nlohmann::json::parse(slurp(set_path(root, 400) / kManifestName));
    m["cycle"] = 390;
    std::ofstream(set_path(root, 400) / kManifestName) << m.dump();
  }
  // The manifest of 300 emptied, that of 200 deleted.
  std::ofstream(set_path(root, 300) / kManifestName, std::ios::trunc);
  fs::remove(set_path(root, 200) / kManifestName);
  const SetChoice c = choose_set(root);
  EXPECT_EQ(c.set.cycle, 100);
  ASSERT_EQ(c.skipped.size(), 3u);
  EXPECT_NE(c.skipped[0].find("says cycle 390, but the set is that of cycle 000000400"), std::string::npos)
      << c.skipped[0];
  EXPECT_NE(c.skipped[1].find("000000300/manifest.json: unreadable"), std::string::npos) << c.skipped[1];
  EXPECT_NE(c.skipped[2].find("000000200: no manifest.json"), std::string::npos) << c.skipped[2];
  // A part whose own cycle is not the set's (copied in from another set), with a manifest made for it.
  const fs::path dir = prepare_set(root, 500);
  for (const char* kind : {"coupler", "fluid"}) {
    PartWriter w(dir / (std::string(kind) + ".h5"), kind);
    w.put_integer("cycle", std::string(kind) == "fluid" ? 533 : 500);
    w.commit();
  }
  write_manifest(dir, 500, 50, {{"parts", {"coupler.h5", "fluid.h5"}}});
  const std::string why = error_of([&] { choose_set(root, 500); });
  EXPECT_NE(why.find("fluid.h5: holds cycle 533, the manifest says cycle 500"), std::string::npos) << why;
  // A set of the format before checksums is refused as such.
  {
    nlohmann::json m = nlohmann::json::parse(slurp(set_path(root, 100) / kManifestName));
    m["format"] = "cosim-checkpoint-set-1";
    m.erase("checksums");
    std::ofstream(set_path(root, 100) / kManifestName) << m.dump();
  }
  EXPECT_NE(error_of([&] { choose_set(root, 100); }).find("an older set without checksums"), std::string::npos);
}
