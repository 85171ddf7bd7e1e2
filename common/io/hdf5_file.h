#pragma once
// Thin RAII wrapper over the HDF5 C API: just what snapshot output (and its tests) need.
//
// Every failure throws std::runtime_error naming the file and the object, with HDF5's own most specific
// message appended. HDF5's automatic error printing to stderr is switched off. Not thread-safe (neither is
// Debian's HDF5 build, serial or OpenMPI).

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace cosim::io {

// Dataset shape, slowest-varying dimension first (C / HDF5 order).
using Hdf5Shape = std::vector<std::uint64_t>;

class Hdf5File {
 public:
  enum class Mode { Create, ReadOnly };  // Create truncates an existing file

  // file_access: 0, or an HDF5 file access property list of the parallel library (MPI-IO, made by
  // parallel::collective_file_access): every rank of its communicator then opens the file together and makes every
  // call below together, with the same arguments but for the part each writes (write_dataset_part).
  Hdf5File(std::filesystem::path path, Mode mode, std::int64_t file_access = 0);
  ~Hdf5File();  // closes silently; call close() to see errors
  Hdf5File(Hdf5File&& other) noexcept;
  Hdf5File& operator=(Hdf5File&& other) noexcept;
  Hdf5File(const Hdf5File&) = delete;
  Hdf5File& operator=(const Hdf5File&) = delete;

  const std::filesystem::path& path() const { return path_; }
  bool is_open() const { return id_ >= 0; }
  void close();

  // Object names are paths from the root, e.g. "/cell/density"; parent groups must exist.
  void create_group(const std::string& name);
  bool exists(const std::string& name) const;

  // 1-D data written as a dataset of `shape`; the product of `shape` must equal data.size().
  void write_dataset(const std::string& name, std::span<const double> data, const Hdf5Shape& shape);
  void write_dataset(const std::string& name, std::span<const std::int64_t> data, const Hdf5Shape& shape);
  void write_dataset(const std::string& name, std::span<const std::uint8_t> data, const Hdf5Shape& shape);

  // A dataset of `shape` of which this process writes the part [offset, offset + count) (data: that part,
  // row-major); in a collective file every rank writes its part in one collective write.
  void write_dataset_part(const std::string& name, std::span<const double> data, const Hdf5Shape& shape,
                          const Hdf5Shape& offset, const Hdf5Shape& count);

  Hdf5Shape dataset_shape(const std::string& name) const;
  std::vector<std::string> dataset_names() const;  // every dataset in the file, as "/group/name", sorted
  std::vector<double> read_doubles(const std::string& name) const;       // flattened, row-major
  std::vector<std::int64_t> read_int64s(const std::string& name) const;  // flattened, row-major
  std::vector<std::uint8_t> read_bytes(const std::string& name) const;   // flattened, row-major
  // The part [offset, offset + count) of a dataset of doubles, row-major; offset and count have one entry per axis
  // of the dataset (std::invalid_argument otherwise, or for a part beyond it).
  std::vector<double> read_doubles_part(const std::string& name, const Hdf5Shape& offset, const Hdf5Shape& count) const;

  // Attributes on an existing object ("/" is the root). Scalars get a scalar dataspace, spans a 1-D one.
  // An existing attribute of the same name is replaced.
  void write_attribute(const std::string& object, const std::string& name, double value);
  void write_attribute(const std::string& object, const std::string& name, std::int64_t value);
  void write_attribute(const std::string& object, const std::string& name, std::span<const double> values);
  void write_attribute(const std::string& object, const std::string& name, std::span<const std::int64_t> values);
  void write_attribute(const std::string& object, const std::string& name, std::string_view value);

  std::vector<double> read_double_attribute(const std::string& object, const std::string& name) const;
  std::vector<std::int64_t> read_int64_attribute(const std::string& object, const std::string& name) const;
  std::string read_string_attribute(const std::string& object, const std::string& name) const;

 private:
  std::int64_t checked_id(const char* action) const;

  std::filesystem::path path_;
  std::int64_t id_ = -1;  // hid_t of the open file, -1 when closed
  bool collective_ = false;
};

}  // namespace cosim::io
