#include "common/io/line_log.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <utility>

namespace cosim::io {

LineLog::LineLog(std::filesystem::path path, std::string_view header) : path_(std::move(path)) {
  fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) throw std::runtime_error(fmt::format("{}: cannot write: {}", path_.string(), std::strerror(errno)));
  append(header);
}

LineLog LineLog::resume(std::filesystem::path path, long long size) {
  LineLog log;
  log.path_ = std::move(path);
  log.fd_ = ::open(log.path_.c_str(), O_WRONLY | O_CLOEXEC);
  if (log.fd_ < 0)
    throw std::runtime_error(fmt::format("{}: cannot continue it: {}", log.path_.string(), std::strerror(errno)));
  const off_t end = ::lseek(log.fd_, 0, SEEK_END);
  if (end < size)
    throw std::runtime_error(fmt::format("{}: {} bytes, shorter than the {} the checkpoint recorded",
                                         log.path_.string(), static_cast<long long>(end), size));
  if (::ftruncate(log.fd_, size) != 0 || ::lseek(log.fd_, size, SEEK_SET) < 0)
    throw std::runtime_error(
        fmt::format("{}: cannot cut it back to the checkpoint: {}", log.path_.string(), std::strerror(errno)));
  log.size_ = size;
  return log;
}

LineLog::LineLog(LineLog&& o) noexcept : path_(std::move(o.path_)), fd_(std::exchange(o.fd_, -1)), size_(o.size_) {}

LineLog& LineLog::operator=(LineLog&& o) noexcept {
  if (this != &o) {
    if (fd_ >= 0) ::close(fd_);
    path_ = std::move(o.path_);
    fd_ = std::exchange(o.fd_, -1);
    size_ = o.size_;
  }
  return *this;
}

LineLog::~LineLog() {
  if (fd_ >= 0) ::close(fd_);
}

void LineLog::append(std::string_view lines) {
  if (fd_ < 0) throw std::runtime_error(fmt::format("{}: not open", path_.string()));
  std::size_t done = 0;
  while (done < lines.size()) {
    const ssize_t n = ::write(fd_, lines.data() + done, lines.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const std::string why = n < 0 ? std::strerror(errno) : "nothing written";
      // The part of the lines that got through is cut off again: the table keeps whole lines only.
      if (::ftruncate(fd_, size_) != 0 || ::lseek(fd_, size_, SEEK_SET) < 0) {}
      throw std::runtime_error(fmt::format("{}: cannot append a line: {}", path_.string(), why));
    }
    done += static_cast<std::size_t>(n);
  }
  size_ += static_cast<long long>(lines.size());
}

}  // namespace cosim::io
