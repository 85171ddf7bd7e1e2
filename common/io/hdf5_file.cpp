#include "common/io/hdf5_file.h"

#include <hdf5.h>

#include <algorithm>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include <fmt/format.h>

namespace cosim::io {
namespace fs = std::filesystem;

namespace {

static_assert(std::is_same_v<hid_t, std::int64_t>, "Hdf5File keeps hid_t in an std::int64_t");

// Error stack walker: keeps the most specific description (the first one walking upward).
herr_t keep_innermost(unsigned n, const H5E_error2_t* err, void* out) {
  if (n == 0 && err->desc != nullptr) *static_cast<std::string*>(out) = err->desc;
  return 0;
}

// Appends HDF5's most specific error message (if any) to `msg` and clears the error stack.
std::string with_hdf5_detail(std::string msg) {
  std::string detail;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, keep_innermost, &detail);
  H5Eclear2(H5E_DEFAULT);
  if (!detail.empty()) msg += ": " + detail;
  return msg;
}

// Owns one HDF5 identifier (dataset, dataspace, type, attribute, ...).
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  ~Handle() {
    if (id_ >= 0) closer_(id_);
  }
  Handle(Handle&& other) noexcept : id_(std::exchange(other.id_, -1)), closer_(other.closer_) {}
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle& operator=(Handle&&) = delete;
  hid_t get() const { return id_; }

 private:
  hid_t id_;
  Closer closer_;
};

// The object an HDF5 call works on, for error messages ("dataset '/cell/rho' in file 'a.h5'").
class Site {
 public:
  Site(const fs::path& file, std::string what) : file_(file), what_(std::move(what)) {}

  [[noreturn]] void fail(std::string_view action) const {
    throw std::runtime_error(
        with_hdf5_detail(fmt::format("HDF5: cannot {} {} in file '{}'", action, what_, file_.string())));
  }
  [[noreturn]] void invalid(std::string_view problem) const {
    throw std::invalid_argument(fmt::format("HDF5: {} in file '{}': {}", what_, file_.string(), problem));
  }
  Handle own(hid_t id, Handle::Closer closer, std::string_view action) const {
    if (id < 0) fail(action);
    return Handle(id, closer);
  }
  void check(herr_t rc, std::string_view action) const {
    if (rc < 0) fail(action);
  }

 private:
  const fs::path& file_;
  std::string what_;
};

Site dataset_site(const fs::path& file, const std::string& name) {
  return Site(file, fmt::format("dataset '{}'", name));
}

Site attribute_site(const fs::path& file, const std::string& object, const std::string& name) {
  return Site(file, fmt::format("attribute '{}' of '{}'", name, object));
}

std::vector<hsize_t> checked_dims(const Hdf5Shape& shape, std::size_t count, const Site& site) {
  if (shape.empty()) site.invalid("shape must have at least one dimension");
  std::uint64_t product = 1;
  for (const std::uint64_t d : shape) product *= d;
  if (product != count) { site.invalid(fmt::format("shape holds {} values but {} were given", product, count)); }
  return {shape.begin(), shape.end()};
}

// The dimensions of a dataspace, slowest first.
std::vector<hsize_t> extent_of(hid_t space, const Site& site) {
  const int rank = H5Sget_simple_extent_ndims(space);
  if (rank < 0) site.fail("query rank of");
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  site.check(H5Sget_simple_extent_dims(space, dims.data(), nullptr), "query shape of");
  return dims;
}

void write_dataset_raw(hid_t file, const Site& site, const std::string& name, const void* data, std::size_t count,
                       const Hdf5Shape& shape, hid_t file_type, hid_t mem_type) {
  const std::vector<hsize_t> dims = checked_dims(shape, count, site);
  const Handle space =
      site.own(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose, "create dataspace of");
  const Handle dset =
      site.own(H5Dcreate2(file, name.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose,
               "create");
  if (count > 0) site.check(H5Dwrite(dset.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), "write");
}

template <class T>
std::vector<T> read_dataset_raw(hid_t file, const Site& site, const std::string& name, hid_t mem_type) {
  const Handle dset = site.own(H5Dopen2(file, name.c_str(), H5P_DEFAULT), H5Dclose, "open");
  const Handle space = site.own(H5Dget_space(dset.get()), H5Sclose, "query");
  const hssize_t n = H5Sget_simple_extent_npoints(space.get());
  if (n < 0) site.fail("query size of");
  std::vector<T> out(static_cast<std::size_t>(n));
  if (n > 0) site.check(H5Dread(dset.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()), "read");
  return out;
}

// Creates (or replaces) attribute `name` on `object` and writes `data` into it.
void write_attribute_raw(hid_t file, const Site& site, const std::string& object, const std::string& name, hid_t space,
                         hid_t type, const void* data) {
  const Handle obj = site.own(H5Oopen(file, object.c_str(), H5P_DEFAULT), H5Oclose, "open the object of");
  const htri_t present = H5Aexists(obj.get(), name.c_str());
  site.check(present, "look up");
  if (present > 0) site.check(H5Adelete(obj.get(), name.c_str()), "replace");
  const Handle attr =
      site.own(H5Acreate2(obj.get(), name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose, "create");
  site.check(H5Awrite(attr.get(), type, data), "write");
}

Handle attribute_space(std::size_t count, bool scalar, const Site& site) {
  if (scalar) return site.own(H5Screate(H5S_SCALAR), H5Sclose, "create dataspace of");
  const hsize_t dim = count;
  return site.own(H5Screate_simple(1, &dim, nullptr), H5Sclose, "create dataspace of");
}

template <class T>
std::vector<T> read_attribute_raw(hid_t file, const Site& site, const std::string& object, const std::string& name,
                                  hid_t mem_type) {
  const Handle attr =
      site.own(H5Aopen_by_name(file, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose, "open");
  const Handle space = site.own(H5Aget_space(attr.get()), H5Sclose, "query");
  const hssize_t n = H5Sget_simple_extent_npoints(space.get());
  if (n < 0) site.fail("query size of");
  std::vector<T> out(static_cast<std::size_t>(n));
  if (n > 0) site.check(H5Aread(attr.get(), mem_type, out.data()), "read");
  return out;
}

std::string read_variable_string(hid_t attr, const Site& site) {
  const Handle mem = site.own(H5Tcopy(H5T_C_S1), H5Tclose, "make string type for");
  site.check(H5Tset_size(mem.get(), H5T_VARIABLE), "make string type for");
  char* raw = nullptr;
  site.check(H5Aread(attr, mem.get(), &raw), "read");
  std::string out = raw != nullptr ? raw : "";
  H5free_memory(raw);
  return out;
}

std::string read_fixed_string(hid_t attr, hid_t file_type, const Site& site) {
  const std::size_t size = H5Tget_size(file_type);
  if (size == 0) site.fail("query string size of");
  const Handle mem = site.own(H5Tcopy(H5T_C_S1), H5Tclose, "make string type for");
  site.check(H5Tset_size(mem.get(), size), "make string type for");
  std::string out(size, '\0');
  site.check(H5Aread(attr, mem.get(), out.data()), "read");
  out.resize(std::min(out.find('\0'), out.size()));
  return out;
}

}  // namespace

// HDF5 must not close files at exit: one whose close failed (a full disk) stays open in the library, and its
// termination handler then crashes flushing it again. Every file is closed explicitly (published or discarded)
// before that. H5dont_atexit must come before any other HDF5 call: at load time.
[[maybe_unused]] const herr_t kNoAtExit = H5dont_atexit();

Hdf5File::Hdf5File(fs::path path, Mode mode, std::int64_t file_access) : path_(std::move(path)) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // we report errors ourselves
  collective_ = file_access != 0;
  if (mode == Mode::Create) {
    id_ = H5Fcreate(path_.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, collective_ ? file_access : H5P_DEFAULT);
  } else {
    id_ = H5Fopen(path_.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  }
  if (id_ < 0) {
    const char* action = mode == Mode::Create ? "create" : "open";
    throw std::runtime_error(with_hdf5_detail(fmt::format("HDF5: cannot {} file '{}'", action, path_.string())));
  }
}

Hdf5File::~Hdf5File() {
  if (id_ >= 0) {
    H5Fclose(id_);
    H5Eclear2(H5E_DEFAULT);
  }
}

Hdf5File::Hdf5File(Hdf5File&& other) noexcept
    : path_(std::move(other.path_)), id_(std::exchange(other.id_, -1)), collective_(other.collective_) {}

Hdf5File& Hdf5File::operator=(Hdf5File&& other) noexcept {
  if (this != &other) {
    if (id_ >= 0) H5Fclose(id_);
    path_ = std::move(other.path_);
    id_ = std::exchange(other.id_, -1);
    collective_ = other.collective_;
  }
  return *this;
}

void Hdf5File::close() {
  if (id_ < 0) return;
  const hid_t id = std::exchange(id_, -1);
  if (H5Fclose(id) < 0) {
    throw std::runtime_error(with_hdf5_detail(fmt::format("HDF5: cannot close file '{}'", path_.string())));
  }
}

std::int64_t Hdf5File::checked_id(const char* action) const {
  if (id_ < 0) throw std::runtime_error(fmt::format("HDF5: cannot {}: file '{}' is closed", action, path_.string()));
  return id_;
}

void Hdf5File::create_group(const std::string& name) {
  const hid_t file = checked_id("create a group");
  const Site site(path_, fmt::format("group '{}'", name));
  site.own(H5Gcreate2(file, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose, "create");
}

bool Hdf5File::exists(const std::string& name) const {
  const hid_t file = checked_id("look up an object");
  const Site site(path_, fmt::format("object '{}'", name));
  std::string prefix;
  std::size_t pos = 0;
  while (pos < name.size()) {
    const std::size_t end = std::min(name.find('/', pos), name.size());
    if (end > pos) {
      prefix += '/';
      prefix.append(name, pos, end - pos);
      const htri_t found = H5Lexists(file, prefix.c_str(), H5P_DEFAULT);
      site.check(found, "look up");
      if (found == 0) return false;
    }
    pos = end + 1;
  }
  return true;
}

void Hdf5File::write_dataset_part(const std::string& name, std::span<const double> data, const Hdf5Shape& shape,
                                  const Hdf5Shape& offset, const Hdf5Shape& count) {
  const hid_t file = checked_id("write a dataset");
  const Site site = dataset_site(path_, name);
  if (offset.size() != shape.size() || count.size() != shape.size())
    site.invalid("offset and count need one entry per axis");
  const std::vector<hsize_t> dims = checked_dims(
      shape,
      [&] {
        std::uint64_t n = 1;
        for (const std::uint64_t d : shape) n *= d;
        return static_cast<std::size_t>(n);
      }(),
      site);
  const std::vector<hsize_t> part = checked_dims(count, data.size(), site);
  const std::vector<hsize_t> start(offset.begin(), offset.end());
  for (std::size_t d = 0; d < dims.size(); ++d)
    if (start[d] + part[d] > dims[d]) site.invalid(fmt::format("part beyond the dataset along axis {}", d));
  const Handle space =
      site.own(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose, "create dataspace of");
  const Handle dset =
      site.own(H5Dcreate2(file, name.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
               H5Dclose, "create");
  const Handle mem =
      site.own(H5Screate_simple(static_cast<int>(part.size()), part.data(), nullptr), H5Sclose, "create dataspace of");
  site.check(H5Sselect_hyperslab(space.get(), H5S_SELECT_SET, start.data(), nullptr, part.data(), nullptr),
             "select the part of");
  const Handle transfer = site.own(H5Pcreate(H5P_DATASET_XFER), H5Pclose, "create the transfer list of");
#ifdef H5_HAVE_PARALLEL
  if (collective_) site.check(H5Pset_dxpl_mpio(transfer.get(), H5FD_MPIO_COLLECTIVE), "set collective writes of");
#endif
  site.check(H5Dwrite(dset.get(), H5T_NATIVE_DOUBLE, mem.get(), space.get(), transfer.get(), data.data()), "write");
}

void Hdf5File::write_dataset(const std::string& name, std::span<const double> data, const Hdf5Shape& shape) {
  write_dataset_raw(checked_id("write a dataset"), dataset_site(path_, name), name, data.data(), data.size(), shape,
                    H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE);
}

void Hdf5File::write_dataset(const std::string& name, std::span<const std::int64_t> data, const Hdf5Shape& shape) {
  write_dataset_raw(checked_id("write a dataset"), dataset_site(path_, name), name, data.data(), data.size(), shape,
                    H5T_STD_I64LE, H5T_NATIVE_INT64);
}

void Hdf5File::write_dataset(const std::string& name, std::span<const std::uint8_t> data, const Hdf5Shape& shape) {
  write_dataset_raw(checked_id("write a dataset"), dataset_site(path_, name), name, data.data(), data.size(), shape,
                    H5T_STD_U8LE, H5T_NATIVE_UINT8);
}

Hdf5Shape Hdf5File::dataset_shape(const std::string& name) const {
  const Site site = dataset_site(path_, name);
  const Handle dset = site.own(H5Dopen2(checked_id("read a dataset"), name.c_str(), H5P_DEFAULT), H5Dclose, "open");
  const Handle space = site.own(H5Dget_space(dset.get()), H5Sclose, "query");
  const std::vector<hsize_t> dims = extent_of(space.get(), site);
  return {dims.begin(), dims.end()};
}

std::vector<double> Hdf5File::read_doubles(const std::string& name) const {
  return read_dataset_raw<double>(checked_id("read a dataset"), dataset_site(path_, name), name, H5T_NATIVE_DOUBLE);
}

std::vector<std::int64_t> Hdf5File::read_int64s(const std::string& name) const {
  return read_dataset_raw<std::int64_t>(checked_id("read a dataset"), dataset_site(path_, name), name,
                                        H5T_NATIVE_INT64);
}

std::vector<double> Hdf5File::read_doubles_part(const std::string& name, const Hdf5Shape& offset,
                                                const Hdf5Shape& count) const {
  const Site site = dataset_site(path_, name);
  const Handle dset = site.own(H5Dopen2(checked_id("read a dataset"), name.c_str(), H5P_DEFAULT), H5Dclose, "open");
  const Handle space = site.own(H5Dget_space(dset.get()), H5Sclose, "query");
  const std::vector<hsize_t> dims = extent_of(space.get(), site);
  if (offset.size() != dims.size() || count.size() != offset.size())
    site.invalid(fmt::format("a part of {} axes asked of a dataset of {}", count.size(), dims.size()));
  const std::vector<hsize_t> start(offset.begin(), offset.end()), part(count.begin(), count.end());
  std::size_t n = 1;
  for (std::size_t d = 0; d < dims.size(); ++d) {
    if (start[d] + part[d] > dims[d]) site.invalid(fmt::format("part beyond the dataset along axis {}", d));
    n *= static_cast<std::size_t>(part[d]);
  }
  std::vector<double> out(n);
  if (n == 0) return out;
  site.check(H5Sselect_hyperslab(space.get(), H5S_SELECT_SET, start.data(), nullptr, part.data(), nullptr),
             "select the part of");
  const Handle mem =
      site.own(H5Screate_simple(static_cast<int>(part.size()), part.data(), nullptr), H5Sclose, "create dataspace of");
  site.check(H5Dread(dset.get(), H5T_NATIVE_DOUBLE, mem.get(), space.get(), H5P_DEFAULT, out.data()), "read");
  return out;
}

namespace {
herr_t collect_dataset(hid_t, const char* name, const H5O_info_t* info, void* out) {
  if (info->type == H5O_TYPE_DATASET) static_cast<std::vector<std::string>*>(out)->push_back(std::string("/") + name);
  return 0;
}
}  // namespace

std::vector<std::string> Hdf5File::dataset_names() const {
  std::vector<std::string> out;
  const Site site(path_, "the datasets");
  site.check(H5Ovisit2(checked_id("list datasets"), H5_INDEX_NAME, H5_ITER_INC, collect_dataset, &out, H5O_INFO_BASIC),
             "list");
  return out;
}

std::vector<std::uint8_t> Hdf5File::read_bytes(const std::string& name) const {
  return read_dataset_raw<std::uint8_t>(checked_id("read a dataset"), dataset_site(path_, name), name,
                                        H5T_NATIVE_UINT8);
}

void Hdf5File::write_attribute(const std::string& object, const std::string& name, double value) {
  const Site site = attribute_site(path_, object, name);
  const Handle space = attribute_space(1, true, site);
  write_attribute_raw(checked_id("write an attribute"), site, object, name, space.get(), H5T_NATIVE_DOUBLE, &value);
}

void Hdf5File::write_attribute(const std::string& object, const std::string& name, std::int64_t value) {
  const Site site = attribute_site(path_, object, name);
  const Handle space = attribute_space(1, true, site);
  write_attribute_raw(checked_id("write an attribute"), site, object, name, space.get(), H5T_NATIVE_INT64, &value);
}

void Hdf5File::write_attribute(const std::string& object, const std::string& name, std::span<const double> values) {
  const Site site = attribute_site(path_, object, name);
  const Handle space = attribute_space(values.size(), false, site);
  write_attribute_raw(checked_id("write an attribute"), site, object, name, space.get(), H5T_NATIVE_DOUBLE,
                      values.data());
}

void Hdf5File::write_attribute(const std::string& object, const std::string& name,
                               std::span<const std::int64_t> values) {
  const Site site = attribute_site(path_, object, name);
  const Handle space = attribute_space(values.size(), false, site);
  write_attribute_raw(checked_id("write an attribute"), site, object, name, space.get(), H5T_NATIVE_INT64,
                      values.data());
}

void Hdf5File::write_attribute(const std::string& object, const std::string& name, std::string_view value) {
  const Site site = attribute_site(path_, object, name);
  const Handle space = attribute_space(1, true, site);
  const Handle type = site.own(H5Tcopy(H5T_C_S1), H5Tclose, "make string type for");
  site.check(H5Tset_size(type.get(), value.size() + 1), "make string type for");
  site.check(H5Tset_strpad(type.get(), H5T_STR_NULLTERM), "make string type for");
  const std::string text(value);  // NUL-terminated copy
  write_attribute_raw(checked_id("write an attribute"), site, object, name, space.get(), type.get(), text.c_str());
}

std::vector<double> Hdf5File::read_double_attribute(const std::string& object, const std::string& name) const {
  return read_attribute_raw<double>(checked_id("read an attribute"), attribute_site(path_, object, name), object, name,
                                    H5T_NATIVE_DOUBLE);
}

std::vector<std::int64_t> Hdf5File::read_int64_attribute(const std::string& object, const std::string& name) const {
  return read_attribute_raw<std::int64_t>(checked_id("read an attribute"), attribute_site(path_, object, name), object,
                                          name, H5T_NATIVE_INT64);
}

std::string Hdf5File::read_string_attribute(const std::string& object, const std::string& name) const {
  const hid_t file = checked_id("read an attribute");
  const Site site = attribute_site(path_, object, name);
  const Handle attr =
      site.own(H5Aopen_by_name(file, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose, "open");
  const Handle type = site.own(H5Aget_type(attr.get()), H5Tclose, "query type of");
  if (H5Tget_class(type.get()) != H5T_STRING) site.fail("read (not a string)");
  const htri_t variable = H5Tis_variable_str(type.get());
  site.check(variable, "query type of");
  return variable > 0 ? read_variable_string(attr.get(), site) : read_fixed_string(attr.get(), type.get(), site);
}

}  // namespace cosim::io
