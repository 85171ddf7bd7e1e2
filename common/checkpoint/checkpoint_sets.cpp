#include "common/checkpoint/checkpoint_sets.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "common/app/version.h"
#include "common/io/atomic_file.h"
#include "common/io/hdf5_file.h"
#include "common/util/sha256.h"

namespace cosim::checkpoint {

namespace fs = std::filesystem;

bool CheckpointPolicy::due(long cycle, double t_prev, double t) const {
  if (cycles > 0 && cycle > 0 && cycle % cycles == 0) return true;
  if (interval > 0 && std::floor(t / interval * (1 + 1e-12)) > std::floor(t_prev / interval * (1 + 1e-12))) return true;
  return false;
}

std::string describe(const CheckpointPolicy& p) {
  if (!p.enabled()) return "no checkpoints";
  std::string every;
  if (p.interval > 0) every = fmt::format("{:g} s", p.interval);
  if (p.cycles > 0) every += fmt::format("{}{} cycles", every.empty() ? "" : " and every ", p.cycles);
  return fmt::format("checkpoints every {}, newest {} kept", every, p.keep);
}

CheckpointPolicy read_checkpoint_policy(config::Node* section) {
  CheckpointPolicy p;
  if (!section) return p;
  p.interval = section->get<double>("interval", 0.0, config::non_negative());
  p.cycles = section->get<int>("cycles", 0, config::int_at_least(0));
  p.keep = section->get<int>("keep", 2, config::int_at_least(1));
  if (!p.enabled()) section->fail("interval", "interval [s] > 0 or cycles > 0 (how often to checkpoint)");
  section->finish();
  return p;
}

fs::path set_path(const fs::path& root, long cycle) { return root / fmt::format("{:09}", cycle); }

fs::path prepare_set(const fs::path& root, long cycle) {
  const fs::path dir = fs::absolute(set_path(root, cycle));
  std::error_code ec;
  fs::remove_all(dir, ec);
  fs::create_directories(dir, ec);
  if (ec) throw std::runtime_error(fmt::format("{}: cannot create the checkpoint set: {}", dir.string(), ec.message()));
  return dir;
}

nlohmann::json scene_record(const std::string& scene_file, const std::vector<std::string>& overrides) {
  std::ifstream in(scene_file);
  nlohmann::json m;
  m["scene"] = std::string(std::istreambuf_iterator<char>(in), {});
  m["overrides"] = overrides;
  m["version"] = app::version();
  m["git_commit"] = app::git_commit();
  return m;
}

namespace {
// The first of `parts` that is not a file in dir, or "".
std::string missing_part(const fs::path& dir, const nlohmann::json& parts) {
  for (const auto& part : parts) {
    std::error_code ec;
    if (!fs::is_regular_file(dir / part.get<std::string>(), ec)) return part.get<std::string>();
  }
  return "";
}

// The digest its writer recorded beside `part` (part_file.h), or the part's own when there is none.
util::FileDigest recorded_digest(const fs::path& part) {
  std::ifstream in(part.string() + kDigestSuffix);
  std::string hex, name;
  if (in >> hex >> name && hex.size() == 64 && name == part.filename().string()) {
    std::error_code ec;
    const auto bytes = fs::file_size(part, ec);
    if (!ec) return {bytes, hex};
  }
  return util::sha256_of_file(part);
}

// The set's folder name, also when the path ends in a separator (`--restart RUN/checkpoints/000000084/`).
std::string set_name(const fs::path& dir) {
  const fs::path p = dir.has_filename() ? dir : dir.parent_path();
  return p.filename().string();
}
}  // namespace

void write_manifest(const fs::path& dir, long cycle, double time, nlohmann::json m) {
  if (!m.contains("parts") || !m["parts"].is_array())
    throw std::invalid_argument("write_manifest: the manifest must list its parts");
  if (const std::string part = missing_part(dir, m["parts"]); !part.empty())
    throw std::runtime_error(fmt::format("{}: part {} is missing: the set is not complete", dir.string(), part));
  nlohmann::json sums = nlohmann::json::object();
  for (const auto& part : m["parts"]) {
    const util::FileDigest d = recorded_digest(dir / part.get<std::string>());
    sums[part.get<std::string>()] = {{"bytes", d.bytes}, {"sha256", d.sha256}};
  }
  m["checksums"] = sums;
  m["format"] = kSetFormat;
  m["cycle"] = cycle;
  m["time"] = time;
  io::write_file_atomically(dir / kManifestName, m.dump(2) + "\n");
}

SetInfo read_set(const fs::path& dir) {
  const fs::path file = dir / kManifestName;
  std::ifstream in(file);
  if (!in)
    throw std::runtime_error(fmt::format("{}: no {}: an incomplete checkpoint set (a process did not confirm its part)",
                                         dir.string(), kManifestName));
  SetInfo s;
  s.dir = dir;
  try {
    in >> s.manifest;
  } catch (const std::exception& e) {
    throw std::runtime_error(fmt::format("{}: unreadable: {}", file.string(), e.what()));
  }
  if (!s.manifest.is_object())
    throw std::runtime_error(fmt::format("{}: not a checkpoint manifest (a JSON object expected)", file.string()));
  const std::string format = s.manifest.value("format", std::string("missing"));
  if (format != kSetFormat)
    throw std::runtime_error(fmt::format("{}: not a checkpoint manifest of this version (format {}, expected {}{})",
                                         file.string(), format, kSetFormat,
                                         format == "cosim-checkpoint-set-1" ? ": an older set without checksums" : ""));
  const auto& cycle = s.manifest["cycle"];
  const auto& parts = s.manifest["parts"];
  const auto& sums = s.manifest["checksums"];
  if (!cycle.is_number_integer() || !s.manifest["time"].is_number() || !parts.is_array() || parts.empty() ||
      !sums.is_object())
    throw std::runtime_error(
        fmt::format("{}: a damaged manifest (cycle, time, parts and checksums expected)", file.string()));
  s.cycle = cycle.get<long>();
  s.time = s.manifest["time"].get<double>();
  // The directory is named for the cycle the set was written at: a manifest that says otherwise was edited.
  if (set_name(dir) != fmt::format("{:09}", s.cycle))
    throw std::runtime_error(
        fmt::format("{}: says cycle {}, but the set is that of cycle {}", file.string(), s.cycle, set_name(dir)));
  for (const auto& part : parts) {
    if (!part.is_string() || !sums.contains(part.get<std::string>()))
      throw std::runtime_error(fmt::format("{}: part {} has no checksum", file.string(), part.dump()));
  }
  if (const std::string part = missing_part(dir, parts); !part.empty())
    throw std::runtime_error(fmt::format("{}: names part {}, which is missing", file.string(), part));
  return s;
}

void verify_part(const SetInfo& s, const std::string& part) {
  const fs::path file = s.dir / part;
  const auto& sum = s.manifest.at("checksums").at(part);
  const std::uint64_t bytes = sum.value("bytes", std::uint64_t{0});
  const std::string sha = sum.value("sha256", std::string());
  std::error_code ec;
  const std::uint64_t size = fs::file_size(file, ec);
  if (ec) throw std::runtime_error(fmt::format("{}: cannot read: {}", file.string(), ec.message()));
  if (size != bytes)
    throw std::runtime_error(fmt::format("{}: {} bytes, the manifest recorded {}: the part is truncated or replaced",
                                         file.string(), size, bytes));
  const util::FileDigest d = util::sha256_of_file(file);
  if (d.sha256 != sha)
    throw std::runtime_error(
        fmt::format("{}: SHA-256 {}, the manifest recorded {}: the part is corrupt", file.string(), d.sha256, sha));
  // The cycle the part holds: a manifest moved to another set, or a part copied from one, is refused. Our parts
  // (HDF5) must hold it; an outside solver's JSON part is checked when it has one; other formats by checksum only.
  std::optional<std::int64_t> held;
  try {
    if (file.extension() == ".h5") {
      const io::Hdf5File h5(file, io::Hdf5File::Mode::ReadOnly);
      const std::vector<std::int64_t> c = h5.read_int64_attribute("/", "cycle");
      held = c.size() == 1 ? c[0] : -1;
    } else if (file.extension() == ".json") {
      std::ifstream in(file);
      const nlohmann::json j = nlohmann::json::parse(in);
      if (j.is_object() && j.contains("cycle")) held = j["cycle"].get<std::int64_t>();
    }
  } catch (const std::exception& e) {
    throw std::runtime_error(fmt::format("{}: not a readable checkpoint part: {}", file.string(), e.what()));
  }
  if (held && *held != s.cycle)
    throw std::runtime_error(
        fmt::format("{}: holds cycle {}, the manifest says cycle {}", file.string(), *held, s.cycle));
}

void verify_set(const SetInfo& s) {
  for (const auto& part : s.manifest.at("parts")) verify_part(s, part.get<std::string>());
}

PartReader open_verified_part(const fs::path& dir, const std::string& file, std::string_view kind) {
  const SetInfo s = read_set(dir);
  bool listed = false;
  for (const auto& part : s.manifest.at("parts")) listed = listed || part.get<std::string>() == file;
  if (!listed) throw std::runtime_error(fmt::format("{}: lists no part {}", (dir / kManifestName).string(), file));
  verify_part(s, file);
  return PartReader(dir / file, kind);
}

namespace {
// The numbered set directories under root, by cycle.
std::vector<std::pair<long, fs::path>> set_dirs(const fs::path& root) {
  std::vector<std::pair<long, fs::path>> out;
  std::error_code ec;
  for (fs::directory_iterator it(root, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.size() != 9 || name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::error_code d;
    if (it->is_directory(d)) out.emplace_back(std::stol(name), it->path());
  }
  std::sort(out.begin(), out.end());
  return out;
}
}  // namespace

std::vector<SetInfo> complete_sets(const fs::path& root) {
  std::vector<SetInfo> out;
  for (const auto& [cycle, dir] : set_dirs(root)) {
    try {
      out.push_back(read_set(dir));
    } catch (const std::exception&) {}  // incomplete: not a candidate
  }
  return out;
}

SetChoice choose_set(const fs::path& root, std::optional<long> cycle) {
  if (cycle) {
    SetChoice c{read_set(set_path(root, *cycle)), {}};
    verify_set(c.set);
    return c;
  }
  const auto dirs = set_dirs(root);
  if (dirs.empty())
    throw std::runtime_error(
        fmt::format("{}: no checkpoint sets (the run wrote none: coupling.checkpoint or "
                    "fluid.checkpoint in the scene turns them on)",
                    root.string()));
  SetChoice c;
  for (auto it = dirs.rbegin(); it != dirs.rend(); ++it) {
    try {
      c.set = read_set(it->second);
      verify_set(c.set);
      return c;
    } catch (const std::exception& e) { c.skipped.push_back(e.what()); }
  }
  std::string why;
  for (const auto& s : c.skipped) why += "\n  " + s;
  throw std::runtime_error(
      fmt::format("{}: {} checkpoint set(s), none complete and intact:{}", root.string(), dirs.size(), why));
}

SetInfo find_set(const fs::path& root, std::optional<long> cycle) { return choose_set(root, cycle).set; }

void clear(const fs::path& root) {
  for (const auto& [cycle, dir] : set_dirs(root)) {
    std::error_code ignored;
    fs::remove_all(dir, ignored);
  }
}

void prune(const fs::path& root, int keep) {
  std::vector<long> complete;  // as a restart counts them: manifest and every part
  for (const SetInfo& s : complete_sets(root)) complete.push_back(s.cycle);
  if (complete.empty()) return;
  const long newest = complete.back();
  const long oldest_kept = complete[complete.size() > static_cast<std::size_t>(keep) ? complete.size() - keep : 0];
  for (const auto& [cycle, dir] : set_dirs(root)) {
    const bool is_complete = std::binary_search(complete.begin(), complete.end(), cycle);
    if ((is_complete && cycle < oldest_kept) || (!is_complete && cycle < newest)) {
      std::error_code ignored;
      fs::remove_all(dir, ignored);
    }
  }
}

}  // namespace cosim::checkpoint
