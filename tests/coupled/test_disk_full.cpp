// A full disk (a file-size limit, `ulimit -f`, with SIGXFSZ ignored: every write past it fails with EFBIG): every
// writer fails cleanly. No process crashes (solid_solver segfaulted in HDF5's exit handler after a failed close),
// the run stops with the cause named, every JSON file that exists parses and every CSV history holds whole lines
// (the coupler's summary was left at 0 bytes and the histories ended mid-line).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "common/checkpoint/checkpoint_sets.h"
#include "coupled_test_util.h"
#include "run_compare.h"

using namespace cosim::test;

namespace {

// Runs `command` under a file-size limit of `kib` KiB; returns its exit status (128 + N when killed by signal N).
int run_limited(int kib, const std::string& command) {
  const std::string cmd = "bash -c \"ulimit -f " + std::to_string(kib) + "; trap '' XFSZ; exec " + command + "\"";
  const int rc = std::system(cmd.c_str());
  if (WIFSIGNALED(rc)) return 128 + WTERMSIG(rc);
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

// Every JSON file under `dir` parses, every CSV file has one column count and ends with a whole line.
void expect_valid_files(const fs::path& dir) {
  int json = 0, csv = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (!e.is_regular_file()) continue;
    const std::string text = read_text(e.path());
    if (e.path().extension() == ".json") {
      ++json;
      EXPECT_TRUE(nlohmann::json::accept(text)) << e.path() << " (" << text.size() << " bytes)";
    } else if (e.path().extension() == ".csv") {
      ++csv;
      ASSERT_FALSE(text.empty()) << e.path();
      EXPECT_EQ(text.back(), '\n') << e.path() << " ends mid-line";
      std::stringstream in(text);
      std::string line;
      std::getline(in, line);
      const auto columns = std::count(line.begin(), line.end(), ',');
      while (std::getline(in, line)) EXPECT_EQ(std::count(line.begin(), line.end(), ','), columns) << e.path();
    }
  }
  EXPECT_GT(json, 0);
  EXPECT_GT(csv, 0);
}

}  // namespace

TEST(DiskFull, EveryWriterOfACoupledRunFailsCleanly) {
  const fs::path dir = run_dir("disk_full");
  fs::remove_all(dir);
  const int rc = run_limited(24, bin("cosim").string() + " run " + scene_file("shock_panel_2d").string() + " --out " +
                                     dir.string() +
                                     " --quiet --set coupling.time.end=2e-4 --set coupling.output.interval=1e-4 > " +
                                     dir.string() + ".log 2>&1");
  std::printf("coupled run with files limited to 24 KiB: exit %d\n", rc);
  EXPECT_NE(rc, 0);
  EXPECT_LT(rc, 128) << "killed by a signal";
  const nlohmann::json summary = nlohmann::json::parse(read_text(dir / "run_summary.json"));
  EXPECT_EQ(summary["status"], "failed");
  EXPECT_NE(summary.dump().find("File too large"), std::string::npos) << summary.dump(2);
  expect_valid_files(dir);
}

TEST(DiskFull, TheSolidSolverStopsWithAnErrorAndNoCrash) {
  const fs::path dir = run_dir("disk_full_solid");
  fs::remove_all(dir);
  const int rc =
      run_limited(100, bin("solid_solver").string() + " " + scene_file("shock_panel_2d_conforming").string() +
                           " --out " + dir.string() + " -q > " + dir.string() + ".log 2>&1");
  EXPECT_EQ(rc, 4) << read_text(fs::path(dir.string() + ".log"));
  EXPECT_NE(read_text(fs::path(dir.string() + ".log")).find("File too large"), std::string::npos);
  EXPECT_EQ(nlohmann::json::parse(read_text(dir / "summary.json"))["status"], "failed");
  expect_valid_files(dir);
  for (const auto& e : fs::directory_iterator(dir)) EXPECT_NE(e.path().extension(), ".tmp") << e.path();
}

namespace {

// A small tmpfs mounted on `dir` for the life of the object; `mounted()` is false where this process may not mount.
class SmallDisk {
 public:
  SmallDisk(const fs::path& dir, int kib) : dir_(dir) {
    fs::create_directories(dir);
    const std::string cmd =
        "mount -t tmpfs -o size=" + std::to_string(kib) + "k tmpfs '" + dir.string() + "' > /dev/null 2>&1";
    mounted_ = std::system(cmd.c_str()) == 0;
  }
  ~SmallDisk() {
    if (mounted_) std::system(("umount '" + dir_.string() + "' > /dev/null 2>&1").c_str());
  }
  bool mounted() const { return mounted_; }

 private:
  fs::path dir_;
  bool mounted_ = false;
};

}  // namespace

TEST(DiskFull, ACheckpointSetThatDoesNotFitIsNeverCompletedAndTheRunResumesFromTheSetBefore) {
  const std::string args = "--set coupling.time.end=0.1 --set coupling.checkpoint.interval=0.03";
  const fs::path full = run_dir("disk_full_ck_reference"), dir = run_dir("disk_full_ck");
  ASSERT_EQ(cosim_run(scene_file("piston_2d"), full, args), 0) << run_logs(full);
  fs::remove_all(dir);
  // The checkpoints go to a disk with room for one set (about 130 KiB here) and not for two.
  const SmallDisk disk(dir / "checkpoints", 192);
  if (!disk.mounted()) GTEST_SKIP() << "cannot mount a tmpfs here (needs root with CAP_SYS_ADMIN)";
  const int rc = cosim_run(scene_file("piston_2d"), dir, args);
  EXPECT_NE(rc, 0);
  EXPECT_LT(rc, 128) << "killed by a signal";
  const std::string summary = read_text(dir / "run_summary.json");
  EXPECT_NE(summary.find("\"failed\""), std::string::npos) << summary;
  EXPECT_NE(summary.find("No space left on device"), std::string::npos) << summary;
  // The set that did not fit has no manifest and no temporary part left; the one before is complete.
  int sets = 0;
  for (const auto& e : fs::directory_iterator(dir / "checkpoints")) {
    ++sets;
    for (const auto& f : fs::directory_iterator(e.path())) EXPECT_NE(f.path().extension(), ".tmp") << f.path();
  }
  EXPECT_EQ(sets, 2);
  const auto complete = cosim::checkpoint::complete_sets(dir / "checkpoints");
  ASSERT_EQ(complete.size(), 1u);
  EXPECT_NEAR(complete[0].time, 0.03, 1e-3);
  expect_valid_files(dir);
  // Resumed from that set with no further sets, the run ends as the uninterrupted one did, bit for bit.
  const std::string resume = bin("cosim").string() + " run " + scene_file("piston_2d").string() + " --restart " +
                             dir.string() + " --quiet --set coupling.time.end=0.1 " +
                             "--set coupling.checkpoint.interval=1 > " + dir.string() + ".resume.log 2>&1";
  ASSERT_EQ(std::system(resume.c_str()), 0) << read_text(dir.string() + ".resume.log") << run_logs(dir);
  expect_same_runs(full, dir, 10);
}
