#include "launcher/restart_check.h"

#include <cstdlib>
#include <map>

namespace cosim::launcher {

namespace {
void flatten(const YAML::Node& n, const std::string& path, std::map<std::string, std::string>& out) {
  if (n.IsMap()) {
    for (const auto& kv : n) flatten(kv.second, path.empty() ? kv.first.Scalar() : path + "." + kv.first.Scalar(), out);
  } else if (n.IsSequence()) {
    for (std::size_t i = 0; i < n.size(); ++i) flatten(n[i], path + "[" + std::to_string(i) + "]", out);
    if (n.size() == 0) out[path] = "[]";
  } else if (n.IsScalar()) {
    out[path] = n.Scalar();
  } else {
    out[path] = "null";
  }
}

bool same_value(const std::string& a, const std::string& b) {
  if (a == b) return true;
  char *ea = nullptr, *eb = nullptr;
  const double x = std::strtod(a.c_str(), &ea), y = std::strtod(b.c_str(), &eb);
  return !a.empty() && !b.empty() && *ea == '\0' && *eb == '\0' && x == y;
}

bool starts_with(const std::string& s, const std::string& p) { return s.rfind(p, 0) == 0; }
}  // namespace

bool restart_may_change(const std::string& key) {
  for (const char* section : {"coupling", "fluid", "solid"}) {
    const std::string s = section;
    if (key == s + ".time.end" || key == s + ".time.max_cycles" || key == s + ".time.max_steps" ||
        key == s + ".threads" || starts_with(key, s + ".checkpoint."))
      return true;
  }
  for (const char* k : {"coupling.timeout", "coupling.heartbeat_interval", "coupling.connect_timeout",
                        "coupling.step_timeout", "coupling.max_message_mb", "name"})
    if (key == k) return true;
  return starts_with(key, "launcher.");
}

std::vector<SceneChange> physics_changes(const config::Node& was, const config::Node& now) {
  std::map<std::string, std::string> a, b;
  flatten(was.yaml(), "", a);
  flatten(now.yaml(), "", b);
  std::vector<SceneChange> out;
  for (const auto& [key, value] : a) {
    const auto it = b.find(key);
    const std::string other = it == b.end() ? "(absent)" : it->second;
    if (!same_value(value, other) && !restart_may_change(key)) out.push_back({key, value, other});
  }
  for (const auto& [key, value] : b)
    if (!a.count(key) && !restart_may_change(key)) out.push_back({key, "(absent)", value});
  return out;
}

}  // namespace cosim::launcher
