#include "common/checkpoint/part_file.h"

#include <fmt/format.h>

#include <cstring>
#include <stdexcept>

#include "common/io/atomic_file.h"
#include "common/io/snapshot_writer.h"
#include "common/util/sha256.h"

namespace cosim::checkpoint {

namespace fs = std::filesystem;

PartWriter::PartWriter(fs::path path, std::string_view kind)
    : path_(std::move(path)), tmp_(io::temp_path_for(path_)), h5_(tmp_, io::Hdf5File::Mode::Create) {
  h5_.write_attribute("/", "format", kPartFormat);
  h5_.write_attribute("/", "kind", kind);
}

PartWriter::PartWriter(fs::path path, std::string_view kind, io::CollectiveWrite& together)
    : path_(std::move(path)),
      tmp_(io::temp_path_for(path_)),
      together_(&together),
      h5_(tmp_, io::Hdf5File::Mode::Create, together.file_access()) {
  h5_.write_attribute("/", "format", kPartFormat);
  h5_.write_attribute("/", "kind", kind);
}

bool PartWriter::leader() const { return !together_ || together_->leader(); }

PartWriter::~PartWriter() {
  if (committed_) return;
  try {
    h5_.close();
  } catch (...) {}  // a failed close (full disk) only leaves the temporary file, removed next
  std::error_code ignored;
  if (leader()) fs::remove(tmp_, ignored);
}

// In a part written together every entry but put_part's is the leader's: the ranks' own values (a timer, a count of
// their own) could otherwise give the datasets other shapes on different ranks, which a collective file cannot hold.
template <class T>
std::vector<T> PartWriter::leaders(std::span<const T> v) const {
  if (!together_) return {v.begin(), v.end()};
  const std::string mine(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  const std::string theirs = together_->from_leader(mine);
  std::vector<T> out(theirs.size() / sizeof(T));
  if (!out.empty()) std::memcpy(out.data(), theirs.data(), theirs.size());
  return out;
}

void PartWriter::put(const std::string& name, std::span<const double> v) {
  const std::vector<double> x = leaders(v);
  h5_.write_dataset("/" + name, x, {x.size()});
}
void PartWriter::put(const std::string& name, std::span<const std::int64_t> v) {
  const std::vector<std::int64_t> x = leaders(v);
  h5_.write_dataset("/" + name, x, {x.size()});
}
void PartWriter::put(const std::string& name, std::span<const std::uint8_t> v) {
  const std::vector<std::uint8_t> x = leaders(v);
  h5_.write_dataset("/" + name, x, {x.size()});
}
void PartWriter::put_part(const std::string& name, std::span<const double> part, const io::Hdf5Shape& shape,
                          const io::Hdf5Shape& offset, const io::Hdf5Shape& count) {
  h5_.write_dataset_part("/" + name, part, shape, offset, count);
}
void PartWriter::put_flags(const std::string& name, const std::vector<char>& flags) {
  put(name, std::vector<std::uint8_t>(flags.begin(), flags.end()));
}
void PartWriter::put_text(const std::string& name, std::string_view text) {
  put(name, std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}
void PartWriter::put_scalar(const std::string& name, double v) {
  h5_.write_attribute("/", name, leaders(std::span<const double>(&v, 1)).at(0));
}
void PartWriter::put_integer(const std::string& name, std::int64_t v) {
  h5_.write_attribute("/", name, leaders(std::span<const std::int64_t>(&v, 1)).at(0));
}

void PartWriter::commit() {
  h5_.close();  // together: every rank's part is in the file when the close returns
  if (!leader()) {
    committed_ = true;
    return;
  }
  // The digest of the bytes as written, before they are published: what a later reader must find.
  const util::FileDigest d = util::sha256_of_file(tmp_);
  io::commit_file(tmp_, path_);
  committed_ = true;
  io::write_file_atomically(path_.string() + kDigestSuffix,
                            fmt::format("{}  {}\n", d.sha256, path_.filename().string()));
}

PartReader::PartReader(fs::path path, std::string_view kind)
    : path_(std::move(path)), h5_([&] {
        std::error_code ec;
        if (!fs::is_regular_file(path_, ec))
          throw std::runtime_error(fmt::format("{}: no such checkpoint part", path_.string()));
        return io::Hdf5File(path_, io::Hdf5File::Mode::ReadOnly);
      }()) {
  std::string format, k;
  try {
    format = h5_.read_string_attribute("/", "format");
    k = h5_.read_string_attribute("/", "kind");
  } catch (const std::exception&) {}
  if (format != kPartFormat)
    throw std::runtime_error(
        fmt::format("{}: not a checkpoint part (format '{}', expected '{}')", path_.string(), format, kPartFormat));
  if (k != kind)
    throw std::runtime_error(
        fmt::format("{}: a checkpoint part of the {}, expected one of the {}", path_.string(), k, kind));
}

bool PartReader::has(const std::string& name) const { return h5_.exists("/" + name); }

void PartReader::check_length(const std::string& name, std::size_t got, std::size_t expected) const {
  if (expected != kAny && got != expected)
    throw std::runtime_error(
        fmt::format("{}: checkpoint entry '{}' holds {} values, this run needs {} (a checkpoint "
                    "of another mesh or scene?)",
                    path_.string(), name, got, expected));
}

std::vector<double> PartReader::doubles(const std::string& name, std::size_t expected) const {
  std::vector<double> v = h5_.read_doubles("/" + name);
  check_length(name, v.size(), expected);
  return v;
}
std::vector<double> PartReader::doubles_part(const std::string& name, const io::Hdf5Shape& shape,
                                             const io::Hdf5Shape& offset, const io::Hdf5Shape& count) const {
  std::size_t total = 1;
  for (const std::uint64_t n : shape) total *= static_cast<std::size_t>(n);
  const io::Hdf5Shape found = h5_.dataset_shape("/" + name);
  if (found == shape) return h5_.read_doubles_part("/" + name, offset, count);
  if (found.size() != 1) {
    std::string want, got;
    for (const std::uint64_t n : shape) want += fmt::format("{}{}", want.empty() ? "" : " x ", n);
    for (const std::uint64_t n : found) got += fmt::format("{}{}", got.empty() ? "" : " x ", n);
    throw std::runtime_error(
        fmt::format("{}: checkpoint entry '{}' is an array of {}, this run needs {} (a "
                    "checkpoint of another mesh or scene?)",
                    path_.string(), name, got, want));
  }
  const std::vector<double> whole = doubles(name, total);
  // Row-major: the part's rows along the last axis, one after the other.
  std::size_t n = 1;
  for (const std::uint64_t c : count) n *= static_cast<std::size_t>(c);
  std::vector<double> out;
  out.reserve(n);
  const std::size_t axes = shape.size(), row = static_cast<std::size_t>(count[axes - 1]);
  std::vector<std::uint64_t> at(axes, 0);  // the position within the part, the last axis left at 0
  for (std::size_t r = 0; row > 0 && r < n / row; ++r) {
    std::size_t flat = 0;
    for (std::size_t d = 0; d < axes; ++d) flat = flat * shape[d] + offset[d] + at[d];
    out.insert(out.end(), whole.begin() + static_cast<std::ptrdiff_t>(flat),
               whole.begin() + static_cast<std::ptrdiff_t>(flat + row));
    for (std::size_t d = axes - 1; d-- > 0;) {
      if (++at[d] < count[d]) break;
      at[d] = 0;
    }
  }
  return out;
}
std::vector<std::int64_t> PartReader::integers(const std::string& name, std::size_t expected) const {
  std::vector<std::int64_t> v = h5_.read_int64s("/" + name);
  check_length(name, v.size(), expected);
  return v;
}
std::vector<std::uint8_t> PartReader::bytes(const std::string& name, std::size_t expected) const {
  std::vector<std::uint8_t> v = h5_.read_bytes("/" + name);
  check_length(name, v.size(), expected);
  return v;
}
std::vector<char> PartReader::flags(const std::string& name) const {
  const std::vector<std::uint8_t> b = bytes(name);
  return std::vector<char>(b.begin(), b.end());
}
std::string PartReader::text(const std::string& name) const {
  const std::vector<std::uint8_t> b = bytes(name);
  return std::string(b.begin(), b.end());
}
double PartReader::scalar(const std::string& name) const {
  const std::vector<double> v = h5_.read_double_attribute("/", name);
  if (v.size() != 1) throw std::runtime_error(fmt::format("{}: checkpoint scalar '{}' missing", path_.string(), name));
  return v[0];
}
std::int64_t PartReader::integer(const std::string& name) const {
  const std::vector<std::int64_t> v = h5_.read_int64_attribute("/", name);
  if (v.size() != 1) throw std::runtime_error(fmt::format("{}: checkpoint integer '{}' missing", path_.string(), name));
  return v[0];
}

}  // namespace cosim::checkpoint
