#pragma once
// Crash-safe file replacement: readers see either the old or the new complete file, never a partial one.

#include <filesystem>
#include <string_view>

namespace cosim::io {

// Temporary name used while writing `p`: same directory, file name + ".tmp" (so a rename is atomic).
// Throws std::invalid_argument when `p` has no file name.
std::filesystem::path temp_path_for(const std::filesystem::path& p);

// Writes `content` to temp_path_for(p), flushes and fsyncs it, renames it over `p` and fsyncs the directory.
// Throws std::system_error naming the file on failure; `p` is then untouched and the temporary file removed.
void write_file_atomically(const std::filesystem::path& p, std::string_view content);

// Publishes a file that was written and closed under a temporary name: fsyncs `from`, renames it to `to`
// (same file system) and fsyncs the directory. Throws std::system_error naming the files on failure.
void commit_file(const std::filesystem::path& from, const std::filesystem::path& to);

}  // namespace cosim::io
