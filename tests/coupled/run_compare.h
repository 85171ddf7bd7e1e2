// Two run directories compared output by output, bit for bit: every snapshot's datasets and time/step
// attributes, every XDMF index and every CSV history; timing.csv by its columns other than the wall-clock times
// (the cycle of every row). Logs, summaries (wall times), checkpoints and the launcher's files are not compared.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "common/io/hdf5_file.h"
#include "coupled_test_util.h"

namespace cosim::test {

struct RunComparison {
  int files = 0, snapshots = 0;
  std::vector<std::string> differences;  // "path: what"
};

// The first field of every line of a CSV file (its header's included).
inline std::vector<std::string> first_column(const fs::path& csv) {
  std::vector<std::string> out;
  std::istringstream in(read_text(csv));
  for (std::string line; std::getline(in, line);) out.push_back(line.substr(0, line.find(',')));
  return out;
}

inline RunComparison compare_runs(const fs::path& a, const fs::path& b) {
  RunComparison r;
  for (auto it = fs::recursive_directory_iterator(a); it != fs::recursive_directory_iterator(); ++it) {
    const fs::path& p = it->path();
    if (it->is_directory() && p.filename() == "checkpoints") {
      it.disable_recursion_pending();
      continue;
    }
    if (!it->is_regular_file()) continue;
    const std::string ext = p.extension().string(), name = p.filename().string();
    if (p.parent_path() == a || name == "progress.txt" || ext == ".json" || ext == ".log" || ext == ".sha256") continue;
    const fs::path q = b / fs::relative(p, a);
    ++r.files;
    if (!fs::exists(q)) {
      r.differences.push_back(q.string() + ": missing");
      continue;
    }
    if (name == "timing.csv") {
      if (first_column(p) != first_column(q)) r.differences.push_back(q.string() + ": other cycles");
      continue;
    }
    if (ext != ".h5") {
      if (read_text(p) != read_text(q)) r.differences.push_back(q.string() + ": content differs");
      continue;
    }
    ++r.snapshots;
    const io::Hdf5File ha(p, io::Hdf5File::Mode::ReadOnly), hb(q, io::Hdf5File::Mode::ReadOnly);
    for (const char* attr : {"time", "step"})
      if (ha.read_double_attribute("/", attr) != hb.read_double_attribute("/", attr))
        r.differences.push_back(q.string() + ": attribute " + attr);
    const std::vector<std::string> names = ha.dataset_names();
    if (names != hb.dataset_names()) r.differences.push_back(q.string() + ": other datasets");
    for (const std::string& d : names)
      if (ha.read_doubles(d) != hb.read_doubles(d)) r.differences.push_back(q.string() + ": " + d);
  }
  return r;
}

inline void expect_same_runs(const fs::path& a, const fs::path& b, int min_snapshots) {
  const RunComparison c = compare_runs(a, b);
  std::printf("%s vs %s: %d files (%d snapshots) compared, %zu differ\n", a.filename().c_str(), b.filename().c_str(),
              c.files, c.snapshots, c.differences.size());
  EXPECT_GE(c.snapshots, min_snapshots);
  for (std::size_t i = 0; i < c.differences.size() && i < 10; ++i) ADD_FAILURE() << c.differences[i];
}

}  // namespace cosim::test
