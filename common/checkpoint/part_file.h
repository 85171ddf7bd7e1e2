// One process's part of a checkpoint set (checkpoint_sets.h): an HDF5 file of named arrays and scalars.
//   PartWriter w(set / "fluid.h5", "fluid");  w.put("U", U);  w.put_scalar("time", t);  w.commit();
//   PartReader r(set / "fluid.h5", "fluid");  U = r.doubles("U", U.size());  t = r.scalar("time");
// The writer fills <file>.tmp and publishes it whole (fsync + rename, io::commit_file): a part is either complete
// or absent; beside it <file>.sha256 (sha256sum's format) records the digest of what was written, for the set's
// manifest (checkpoint_sets.h). The reader checks the format, the kind and every array's length, naming the file
// and the entry; open_verified_part() first checks the file against its set's manifest.
// Layout: root attributes format = "cosim-checkpoint-1", kind, and one attribute per scalar; one dataset per array
// (double, int64 or uint8; texts are uint8 datasets).
#pragma once

#include <cstdint>
#include <filesystem>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "common/io/hdf5_file.h"

namespace cosim::io {
class CollectiveWrite;
}

namespace cosim::checkpoint {

inline constexpr std::string_view kPartFormat = "cosim-checkpoint-1";
inline constexpr const char* kDigestSuffix = ".sha256";

class PartWriter {
 public:
  // Throws std::runtime_error naming the file when it cannot be created.
  PartWriter(std::filesystem::path path, std::string_view kind);
  // The ranks of `together` write the part together (collective HDF5); `together` outlives the writer.
  PartWriter(std::filesystem::path path, std::string_view kind, io::CollectiveWrite& together);
  ~PartWriter();  // an uncommitted part is discarded (its temporary file removed)
  PartWriter(const PartWriter&) = delete;
  PartWriter& operator=(const PartWriter&) = delete;

  void put(const std::string& name, std::span<const double> v);
  void put(const std::string& name, std::span<const std::int64_t> v);
  void put(const std::string& name, std::span<const std::uint8_t> v);
  // An array of `shape` (slowest axis first) of which this writer holds the part [offset, offset + count).
  void put_part(const std::string& name, std::span<const double> part, const io::Hdf5Shape& shape,
                const io::Hdf5Shape& offset, const io::Hdf5Shape& count);
  void put_flags(const std::string& name, const std::vector<char>& flags);  // as bytes (0/1 per entry)
  void put_text(const std::string& name, std::string_view text);
  void put_scalar(const std::string& name, double v);
  void put_integer(const std::string& name, std::int64_t v);
  // Closes and publishes the file with its digest file; throws std::runtime_error (disk full: the part stays absent).
  void commit();

 private:
  std::filesystem::path path_, tmp_;
  io::CollectiveWrite* together_ = nullptr;
  io::Hdf5File h5_;
  bool committed_ = false;
  bool leader() const;
  template <class T>
  std::vector<T> leaders(std::span<const T> v) const;
};

class PartReader {
 public:
  static constexpr std::size_t kAny = std::numeric_limits<std::size_t>::max();
  // Throws std::runtime_error naming the file when it is missing, unreadable, or not a part of this kind.
  PartReader(std::filesystem::path path, std::string_view kind);

  bool has(const std::string& name) const;
  // The array `name`; with `expected` != kAny its length must be that (std::runtime_error otherwise).
  std::vector<double> doubles(const std::string& name, std::size_t expected = kAny) const;
  // The part [offset, offset + count) of the array `name` of `shape` (put_part); an array of that many values with
  // one axis (a part written whole before arrays had shapes) is read whole and cut.
  std::vector<double> doubles_part(const std::string& name, const io::Hdf5Shape& shape, const io::Hdf5Shape& offset,
                                   const io::Hdf5Shape& count) const;
  std::vector<std::int64_t> integers(const std::string& name, std::size_t expected = kAny) const;
  std::vector<std::uint8_t> bytes(const std::string& name, std::size_t expected = kAny) const;
  std::vector<char> flags(const std::string& name) const;
  std::string text(const std::string& name) const;
  double scalar(const std::string& name) const;
  std::int64_t integer(const std::string& name) const;
  const std::filesystem::path& path() const { return path_; }

 private:
  void check_length(const std::string& name, std::size_t got, std::size_t expected) const;
  std::filesystem::path path_;
  io::Hdf5File h5_;
};

}  // namespace cosim::checkpoint
