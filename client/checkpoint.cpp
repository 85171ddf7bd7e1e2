// The C interface's checkpoint parts: writing this solver's part with its digest file, and reading a part back
// only after it matched its set's manifest (format cosim-checkpoint-set-2, docs/checkpoint_restart.md). The
// checks and their messages are those of common/checkpoint/checkpoint_sets.cpp (read_set, verify_part), without
// its HDF5 parts: an outside solver's part is checked by size, SHA-256 and the set's cycle.
#include <fmt/format.h>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "client/handle.h"
#include "common/io/atomic_file.h"
#include "common/util/sha256.h"

namespace fs = std::filesystem;
using namespace cosim;
using client_detail::connected;
using client_detail::Corrupt;
using client_detail::guarded;

namespace {

constexpr const char* kSetFormat = "cosim-checkpoint-set-2";  // checkpoint::kSetFormat
constexpr const char* kManifest = "manifest.json";

struct Recorded {
  long long cycle = 0;
  double time = 0;
  long long bytes = 0;
  std::string sha256;
};

std::string text(const char* s, const char* what) {
  if (!s || !*s) throw std::invalid_argument(std::string(what) + ": empty or null");
  return s;
}

// A part name is a file in the set directory, nothing above or below it.
void check_part_name(const std::string& part) {
  if (part.find('/') != std::string::npos || part == "." || part == ".." || part == kManifest)
    throw std::invalid_argument("part '" + part + "': expected a file name in the set directory (not manifest.json)");
}

// What the manifest of set `dir` records of `part`, after the checks every restarting process makes: the format,
// the cycle against the directory's name, the part listed with a checksum.
Recorded recorded(const fs::path& dir, const std::string& part) {
  const fs::path file = dir / kManifest;
  std::ifstream in(file);
  if (!in)
    throw Corrupt(fmt::format("{}: no {}: an incomplete checkpoint set (a process did not confirm its part)",
                              dir.string(), kManifest));
  nlohmann::json m;
  try {
    in >> m;
  } catch (const std::exception& e) { throw Corrupt(fmt::format("{}: unreadable: {}", file.string(), e.what())); }
  if (!m.is_object())
    throw Corrupt(fmt::format("{}: not a checkpoint manifest (a JSON object expected)", file.string()));
  const std::string format = m.value("format", std::string("missing"));
  if (format != kSetFormat)
    throw Corrupt(fmt::format("{}: not a checkpoint manifest of this version (format {}, expected {})", file.string(),
                              format, kSetFormat));
  if (!m["cycle"].is_number_integer() || !m["time"].is_number() || !m["parts"].is_array() ||
      !m["checksums"].is_object())
    throw Corrupt(fmt::format("{}: a damaged manifest (cycle, time, parts and checksums expected)", file.string()));
  Recorded r;
  r.cycle = m["cycle"].get<long long>();
  r.time = m["time"].get<double>();
  // The directory is named for the cycle the set was written at: a manifest that says otherwise was edited.
  const std::string name = fs::absolute(dir).lexically_normal().filename().string();
  const std::string set = name.empty() ? fs::absolute(dir).lexically_normal().parent_path().filename().string() : name;
  if (set != fmt::format("{:09}", r.cycle))
    throw Corrupt(fmt::format("{}: says cycle {}, but the set is that of cycle {}", file.string(), r.cycle, set));
  bool listed = false;
  for (const auto& p : m["parts"]) listed = listed || (p.is_string() && p.get<std::string>() == part);
  const auto& sums = m["checksums"];
  if (!listed || !sums.contains(part) || !sums[part].is_object())
    throw Corrupt(fmt::format("{}: lists no part {} with a checksum", file.string(), part));
  r.bytes = sums[part].value("bytes", -1LL);
  r.sha256 = sums[part].value("sha256", std::string());
  return r;
}

// The part's bytes, read once, then checked against what the manifest recorded.
std::vector<std::uint8_t> read_checked(const fs::path& file, const Recorded& r) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error(fmt::format("{}: cannot read the checkpoint part", file.string()));
  std::vector<std::uint8_t> data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw std::runtime_error(fmt::format("{}: read failed", file.string()));
  if (static_cast<long long>(data.size()) != r.bytes)
    throw Corrupt(fmt::format("{}: {} bytes, the manifest recorded {}: the part is truncated or replaced",
                              file.string(), data.size(), r.bytes));
  util::Sha256 h;
  h.update(data);
  const std::string sha = h.hex_digest();
  if (sha != r.sha256)
    throw Corrupt(
        fmt::format("{}: SHA-256 {}, the manifest recorded {}: the part is corrupt", file.string(), sha, r.sha256));
  return data;
}

// Writes `bytes` of `data` as dir/part: temporary file, fsync, rename (whole or absent), then the digest file
// beside it in sha256sum's format, which the coupler's manifest takes the checksum from.
void write_part(const fs::path& dir, const std::string& part, const void* data, long long bytes) {
  const fs::path path = dir / part, tmp = io::temp_path_for(path);
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (bytes > 0) out.write(static_cast<const char*>(data), static_cast<std::streamsize>(bytes));
    out.close();
    if (!out) {
      std::error_code ec;
      fs::remove(tmp, ec);
      throw std::runtime_error(fmt::format("{}: cannot write the checkpoint part", tmp.string()));
    }
  }
  util::Sha256 h;
  h.update({static_cast<const std::uint8_t*>(data), static_cast<std::size_t>(bytes)});
  const std::string sha = h.hex_digest();
  io::commit_file(tmp, path);
  io::write_file_atomically(path.string() + ".sha256", fmt::format("{}  {}\n", sha, part));
}

}  // namespace

extern "C" {

int cosim_write_part(cosim_client* c, const char* part, const void* data, long long bytes) {
  return guarded([&] {
    auto& client = connected(c);
    const std::string name = text(part, "cosim_write_part: part");
    check_part_name(name);
    if (bytes < 0 || (bytes > 0 && !data))
      throw std::invalid_argument("cosim_write_part: data and bytes >= 0 expected");
    if (c->directive.kind != coupling::Directive::Kind::Checkpoint || c->directive.directory.empty())
      throw std::logic_error("cosim_write_part: no checkpoint was asked for (answer a COSIM_CHECKPOINT directive)");
    write_part(c->directive.directory, name, data, bytes);
    client.confirm_checkpoint(name, static_cast<std::uint64_t>(bytes));
  });
}

int cosim_client_verify_part(const char* set, const char* part, long long* bytes, char sha256[65], long long* cycle,
                             double* time) {
  return guarded([&] {
    const fs::path dir = text(set, "cosim_client_verify_part: set");
    const std::string name = text(part, "cosim_client_verify_part: part");
    check_part_name(name);
    const Recorded r = recorded(dir, name);
    read_checked(dir / name, r);
    if (bytes) *bytes = r.bytes;
    if (sha256) std::snprintf(sha256, 65, "%s", r.sha256.c_str());  // 64 hex digits: it matched
    if (cycle) *cycle = r.cycle;
    if (time) *time = r.time;
  });
}

int cosim_read_part(const char* set, const char* part, void* out, long long capacity, long long* length) {
  return guarded([&] {
    const fs::path dir = text(set, "cosim_read_part: set");
    const std::string name = text(part, "cosim_read_part: part");
    check_part_name(name);
    if (!length || capacity < 0 || (capacity > 0 && !out))
      throw std::invalid_argument("cosim_read_part: output, capacity >= 0 and length expected");
    const std::vector<std::uint8_t> data = read_checked(dir / name, recorded(dir, name));
    *length = static_cast<long long>(data.size());
    if (static_cast<long long>(data.size()) > capacity)
      throw std::invalid_argument(fmt::format("cosim_read_part: {} holds {} bytes, more than the capacity {}",
                                              (dir / name).string(), data.size(), capacity));
    if (!data.empty()) std::memcpy(out, data.data(), data.size());
  });
}

}  // extern "C"
