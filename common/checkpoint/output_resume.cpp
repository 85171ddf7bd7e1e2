#include "common/checkpoint/output_resume.h"

#include <vector>

namespace cosim::checkpoint {

namespace {
constexpr char kSeparator = '\x1e';  // ASCII record separator: never in an XDMF entry
}

void put_series(PartWriter& w, const std::string& name, const io::SnapshotSeries& s) {
  std::string joined;
  for (const std::string& e : s.entries()) {
    joined += e;
    joined += kSeparator;
  }
  w.put_text("series." + name, joined);
}

void resume_series(const PartReader& r, const std::string& name, io::SnapshotSeries& s) {
  const std::string joined = r.text("series." + name);
  std::vector<std::string> entries;
  for (std::size_t start = 0, end; (end = joined.find(kSeparator, start)) != std::string::npos; start = end + 1)
    entries.push_back(joined.substr(start, end - start));
  s.resume(std::move(entries));
}

void put_log(PartWriter& w, const std::string& name, const io::LineLog& log) {
  w.put_integer("log." + name, log.size());
}

io::LineLog resume_log(const PartReader& r, const std::string& name, const std::filesystem::path& path) {
  return io::LineLog::resume(path, r.integer("log." + name));
}

}  // namespace cosim::checkpoint
