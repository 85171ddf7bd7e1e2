#include "common/io/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <system_error>

#include <fmt/format.h>

namespace cosim::io {
namespace fs = std::filesystem;

namespace {

[[noreturn]] void throw_errno(int err, const std::string& what) {
  throw std::system_error(err, std::generic_category(), what);
}

// Owns a POSIX file descriptor.
class FileDescriptor {
 public:
  explicit FileDescriptor(int fd) : fd_(fd) {}
  ~FileDescriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;

  int get() const { return fd_; }
  // Closes now and reports the result (close can report delayed write errors).
  int close_now() {
    const int rc = ::close(fd_);
    fd_ = -1;
    return rc;
  }

 private:
  int fd_;
};

void write_all(int fd, std::string_view content, const fs::path& p) {
  while (!content.empty()) {
    const ssize_t n = ::write(fd, content.data(), content.size());
    if (n < 0) {
      if (errno == EINTR) continue;
      throw_errno(errno, fmt::format("cannot write '{}'", p.string()));
    }
    content.remove_prefix(static_cast<std::size_t>(n));
  }
}

void fsync_fd(int fd, const fs::path& p) {
  while (::fsync(fd) != 0) {
    if (errno != EINTR) throw_errno(errno, fmt::format("cannot fsync '{}'", p.string()));
  }
}

void fsync_path(const fs::path& p) {
  FileDescriptor fd(::open(p.c_str(), O_RDONLY | O_CLOEXEC));
  if (fd.get() < 0) throw_errno(errno, fmt::format("cannot open '{}'", p.string()));
  fsync_fd(fd.get(), p);
}

// Makes a rename durable. Best effort: some file systems refuse fsync on directories.
void sync_directory_of(const fs::path& p) {
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  (void)::fsync(fd);
  ::close(fd);
}

void rename_file(const fs::path& from, const fs::path& to) {
  if (std::rename(from.c_str(), to.c_str()) != 0) {
    throw_errno(errno, fmt::format("cannot rename '{}' to '{}'", from.string(), to.string()));
  }
}

void remove_quietly(const fs::path& p) {
  std::error_code ignored;
  fs::remove(p, ignored);
}

// Writes, flushes and closes `tmp`, then renames it to `p`.
void write_and_rename(const fs::path& tmp, const fs::path& p, std::string_view content) {
  FileDescriptor fd(::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644));
  if (fd.get() < 0) {
    throw_errno(errno, fmt::format("cannot create '{}' (to replace '{}')", tmp.string(), p.string()));
  }
  try {
    write_all(fd.get(), content, tmp);
    fsync_fd(fd.get(), tmp);
    if (fd.close_now() != 0) throw_errno(errno, fmt::format("cannot close '{}'", tmp.string()));
    rename_file(tmp, p);
  } catch (...) {
    remove_quietly(tmp);
    throw;
  }
}

}  // namespace

fs::path temp_path_for(const fs::path& p) {
  if (!p.has_filename()) {
    throw std::invalid_argument(fmt::format("temp_path_for: '{}' has no file name", p.string()));
  }
  fs::path tmp = p;
  tmp += ".tmp";
  return tmp;
}

void write_file_atomically(const fs::path& p, std::string_view content) {
  write_and_rename(temp_path_for(p), p, content);
  sync_directory_of(p);
}

void commit_file(const fs::path& from, const fs::path& to) {
  fsync_path(from);
  rename_file(from, to);
  sync_directory_of(to);
}

}  // namespace cosim::io
