#include "common/checkpoint/checkpoint_sets.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "common/app/version.h"
#include "common/io/atomic_file.h"

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
}  // namespace

void write_manifest(const fs::path& dir, long cycle, double time, nlohmann::json m) {
  if (!m.contains("parts") || !m["parts"].is_array())
    throw std::invalid_argument("write_manifest: the manifest must list its parts");
  if (const std::string part = missing_part(dir, m["parts"]); !part.empty())
    throw std::runtime_error(fmt::format("{}: part {} is missing: the set is not complete", dir.string(), part));
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
  if (s.manifest.value("format", "") != kSetFormat)
    throw std::runtime_error(fmt::format("{}: not a checkpoint manifest (format {})", file.string(),
                                         s.manifest.value("format", std::string("missing"))));
  s.cycle = s.manifest.value("cycle", -1L);
  s.time = s.manifest.value("time", 0.0);
  if (const std::string part = missing_part(dir, s.manifest.value("parts", nlohmann::json::array())); !part.empty())
    throw std::runtime_error(fmt::format("{}: names part {}, which is missing", file.string(), part));
  return s;
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

SetInfo find_set(const fs::path& root, std::optional<long> cycle) {
  if (cycle) return read_set(set_path(root, *cycle));
  const std::vector<SetInfo> sets = complete_sets(root);
  if (sets.empty()) {
    const auto dirs = set_dirs(root);
    throw std::runtime_error(dirs.empty()
                                 ? fmt::format("{}: no checkpoint sets (the run wrote none: coupling.checkpoint or "
                                               "fluid.checkpoint in the scene turns them on)",
                                               root.string())
                                 : fmt::format("{}: {} checkpoint set(s), none complete", root.string(), dirs.size()));
  }
  return sets.back();
}

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
