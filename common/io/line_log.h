// An append-only text table (CSV histories): every line goes to the file in one write, or not at all. When the
// disk is full (or a file-size limit is reached) the partial line is cut off again, so the file stays a valid
// table of whole lines, and the error names the file.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace cosim::io {

class LineLog {
 public:
  LineLog() = default;
  // Creates (truncates) `path` and writes `header` (one or more whole lines). Throws std::runtime_error naming the
  // file when it cannot.
  LineLog(std::filesystem::path path, std::string_view header);
  // Continues a table a checkpoint recorded at `size` bytes: lines written after it (by the run that stopped) are
  // cut off. Throws std::runtime_error naming the file when it is missing or shorter than `size`.
  static LineLog resume(std::filesystem::path path, long long size);
  LineLog(LineLog&& o) noexcept;
  LineLog& operator=(LineLog&& o) noexcept;
  LineLog(const LineLog&) = delete;
  LineLog& operator=(const LineLog&) = delete;
  ~LineLog();

  // Appends `lines` (ending in a newline) whole; on failure the file is cut back to its previous length and
  // std::runtime_error names the file and the reason.
  void append(std::string_view lines);
  const std::filesystem::path& path() const { return path_; }
  long long size() const { return size_; }  // bytes of whole lines written (what a checkpoint records)

 private:
  std::filesystem::path path_;
  int fd_ = -1;
  long long size_ = 0;
};

}  // namespace cosim::io
