#include "common/config/config.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace cosim::config {

namespace {
std::string fmt_num(double v) { return fmt::format("{:g}", v); }

// Walk (and create) the path a.b.0.c inside root; returns the node to assign.
void apply_override(YAML::Node root, const std::string& assignment, DocumentContext& ctx) {
  auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw ConfigError(fmt::format("--set {}: expected key.path=value", assignment));
  std::string path = assignment.substr(0, eq);
  std::string value = assignment.substr(eq + 1);
  YAML::Node parsed;
  try {
    parsed = YAML::Load(value);
  } catch (const YAML::Exception& e) {
    throw ConfigError(fmt::format("--set {}: value is not valid YAML: {}", path, e.msg));
  }
  std::vector<std::string> parts;
  std::stringstream ss(path);
  for (std::string p; std::getline(ss, p, '.');) {
    if (p.empty()) throw ConfigError(fmt::format("--set {}: empty component in key path", path));
    parts.push_back(p);
  }
  YAML::Node cur(root);
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const std::string& p = parts[i];
    const bool last = i + 1 == parts.size();
    bool is_index = !p.empty() && std::all_of(p.begin(), p.end(), ::isdigit);
    YAML::Node next;
    if (cur.IsSequence()) {
      if (!is_index) throw ConfigError(fmt::format("--set {}: '{}' is a list, expected a numeric index", path, p));
      std::size_t idx = std::stoul(p);
      if (idx >= cur.size())
        throw ConfigError(fmt::format("--set {}: index {} out of range (list has {} entries)", path, idx, cur.size()));
      if (last) {
        cur[idx] = parsed;
        break;
      }
      next.reset(cur[idx]);
    } else {
      if (cur.IsScalar())
        throw ConfigError(fmt::format("--set {}: '{}' is a value, not a section", path, parts[i - 1]));
      if (last) {
        cur[p] = parsed;
        break;
      }
      if (!cur[p] || cur[p].IsNull()) cur[p] = YAML::Node(YAML::NodeType::Map);
      next.reset(cur[p]);
    }
    cur.reset(next);
  }
  ctx.overridden.insert(path);
}

Node make_root(YAML::Node root, const std::string& name, const std::vector<std::string>& overrides) {
  auto ctx = std::make_shared<DocumentContext>();
  ctx->file = name;
  if (!root || root.IsNull()) root = YAML::Node(YAML::NodeType::Map);
  if (!root.IsMap()) throw ConfigError(fmt::format("{}:1: expected a YAML mapping of sections at the top level", name));
  for (const auto& o : overrides) apply_override(root, o, *ctx);
  return Node(root, "", ctx);
}
}  // namespace

Check<double> positive() {
  return [](const double& v) { return v > 0 ? std::string() : std::string("a number > 0"); };
}
Check<double> non_negative() {
  return [](const double& v) { return v >= 0 ? std::string() : std::string("a number >= 0"); };
}
Check<double> in_range(double lo, double hi) {
  return [lo, hi](const double& v) {
    return (v >= lo && v <= hi) ? std::string() : fmt::format("a number in [{}, {}]", fmt_num(lo), fmt_num(hi));
  };
}
Check<double> speed() {
  return [](const double& v) { return std::abs(v) <= 1e5 ? std::string() : std::string("speeds of at most 1e5 m/s"); };
}
std::array<double, 3> read_point(Node& n, const std::string& key, int dim, std::optional<std::vector<double>> fallback,
                                 Check<double> check) {
  const std::vector<double> v = n.get_vector(key, static_cast<std::size_t>(dim), static_cast<std::size_t>(dim),
                                             std::move(fallback), std::move(check));
  std::array<double, 3> out{0, 0, 0};
  for (int d = 0; d < dim; ++d) out[static_cast<std::size_t>(d)] = v[static_cast<std::size_t>(d)];
  return out;
}
Check<double> in_open_closed(double lo, double hi) {
  return [lo, hi](const double& v) {
    return (v > lo && v <= hi) ? std::string() : fmt::format("a number in ({}, {}]", fmt_num(lo), fmt_num(hi));
  };
}
Check<int> int_at_least(int lo) {
  return [lo](const int& v) { return v >= lo ? std::string() : fmt::format("an integer >= {}", lo); };
}
Check<std::string> one_of(std::vector<std::string> choices) {
  return [choices](const std::string& v) {
    if (std::find(choices.begin(), choices.end(), v) != choices.end()) return std::string();
    std::string list;
    for (const auto& c : choices) list += (list.empty() ? "" : " | ") + c;
    std::set<std::string> cs(choices.begin(), choices.end());
    std::string best = closest(v, cs);
    return fmt::format("one of {}{}", list, best.empty() ? "" : fmt::format(" (did you mean '{}'?)", best));
  };
}

namespace {
// The length of the printable UTF-8 character at text[i] (1 for printable ASCII), 0 when the byte there must be
// escaped: a control character, an invalid, overlong or surrogate sequence, a C1 control (U+0080..U+009F).
std::size_t printable_char(const std::string& text, std::size_t i) {
  const auto b = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned c = b(i);
  if (c < 0x80) return c >= 0x20 && c != 0x7f ? 1 : 0;
  const std::size_t len = c >= 0xc2 && c <= 0xdf ? 2 : c >= 0xe0 && c <= 0xef ? 3 : c >= 0xf0 && c <= 0xf4 ? 4 : 0;
  if (len == 0 || i + len > text.size()) return 0;
  unsigned cp = c & (0xff >> (len + 1));
  for (std::size_t k = 1; k < len; ++k) {
    if ((b(i + k) & 0xc0) != 0x80) return 0;
    cp = (cp << 6) | (b(i + k) & 0x3f);
  }
  const unsigned least[] = {0, 0, 0x80, 0x800, 0x10000};
  if (cp < least[len] || cp > 0x10ffff || (cp >= 0xd800 && cp <= 0xdfff) || cp < 0xa0) return 0;
  return len;
}
}  // namespace

std::string printable(const std::string& text) {
  std::string out;
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t n = printable_char(text, i);
    if (n == 0) {
      out += fmt::format("\\x{:02x}", static_cast<unsigned char>(text[i++]));
    } else {
      out.append(text, i, n);
      i += n;
    }
  }
  return out;
}

bool is_printable(const std::string& text) {
  for (std::size_t i = 0, n = 0; i < text.size(); i += n)
    if ((n = printable_char(text, i)) == 0) return false;
  return true;
}

Node::Node(YAML::Node node, std::string path, std::shared_ptr<DocumentContext> ctx)
    : node_(node), path_(std::move(path)), ctx_(std::move(ctx)) {}

bool Node::has(const std::string& key) const {
  if (!node_.IsMap()) return false;
  YAML::Node n = node_[key];
  return n && !n.IsNull();
}

bool Node::child_is_map(const std::string& key) const {
  if (!node_.IsMap()) return false;
  YAML::Node n = node_[key];
  return n && n.IsMap();
}

YAML::Node Node::at(const std::string& key) const {
  if (!node_.IsMap()) fail("", "a section (key: value mapping), got " + describe(node_));
  return node_[key];
}

std::string Node::key_path(const std::string& key) const {
  if (key.empty()) return path_;
  return path_.empty() ? key : path_ + "." + key;
}

std::string Node::describe(const YAML::Node& n) const {
  if (!n) return "nothing";
  switch (n.Type()) {
    case YAML::NodeType::Scalar: return "'" + n.Scalar() + "'";
    case YAML::NodeType::Sequence: return "a list";
    case YAML::NodeType::Map: return "a section";
    default: return "nothing";
  }
}

std::string Node::where(const std::string& key) const {
  std::string kp = key_path(key);
  for (const auto& o : ctx_->overridden)
    if (kp == o || kp.rfind(o + ".", 0) == 0) return fmt::format("--set {}: {}", o, kp);
  YAML::Node n = node_;
  if (!key.empty() && node_.IsMap() && node_[key]) n.reset(node_[key]);
  int line = n.Mark().is_null() ? -1 : n.Mark().line + 1;
  if (line < 0) line = node_.Mark().is_null() ? 1 : node_.Mark().line + 1;
  return fmt::format("{}:{}: {}", ctx_->file, line, kp.empty() ? "(top level)" : kp);
}

void Node::fail(const std::string& key, const std::string& expected) const {
  throw ConfigError(fmt::format("{}: expected {}", where(key), expected));
}

std::vector<double> Node::get_vector(const std::string& key, std::size_t min_len, std::size_t max_len,
                                     std::optional<std::vector<double>> fallback, Check<double> check) {
  used_.insert(key);
  YAML::Node n = at(key);
  if (!n || n.IsNull()) {
    if (fallback) return *fallback;
    fail(key,
         fmt::format("a list of {} to {} numbers, but the key is missing{}", min_len, max_len, typo_of_missing(key)));
  }
  std::string expected = min_len == max_len ? fmt::format("a list of {} numbers", min_len)
                                            : fmt::format("a list of {} to {} numbers", min_len, max_len);
  if (n.IsScalar() && min_len <= 1) {  // a single number is accepted for a 1-element list
    Node self(node_, path_, ctx_);
    double v = self.get<double>(key, 0.0, check);
    return {v};
  }
  if (!n.IsSequence() || n.size() < min_len || n.size() > max_len) fail(key, expected + ", got " + describe(n));
  std::vector<double> out;
  for (std::size_t i = 0; i < n.size(); ++i) {
    double v = 0;
    if (!detail::convert(n[i], v)) fail(key, expected + ", entry " + std::to_string(i) + " is " + describe(n[i]));
    if (check) {
      std::string e = check(v);
      if (!e.empty()) fail(key, fmt::format("entries that are {}, entry {} is {}", e, i, describe(n[i])));
    }
    out.push_back(v);
  }
  return out;
}

Node Node::child(const std::string& key) {
  used_.insert(key);
  YAML::Node n = at(key);
  if (!n || n.IsNull()) fail(key, "a section, but the key is missing" + typo_of_missing(key));
  if (!n.IsMap()) fail(key, "a section (key: value mapping), got " + describe(n));
  return Node(n, key_path(key), ctx_);
}

std::optional<Node> Node::optional_child(const std::string& key) {
  if (!has(key)) {
    used_.insert(key);
    return std::nullopt;
  }
  return child(key);
}

Node Node::child_or_empty(const std::string& key) {
  if (!has(key)) {
    used_.insert(key);
    return Node(YAML::Node(YAML::NodeType::Map), key_path(key), ctx_);
  }
  return child(key);
}

std::string scene_base_dir(const std::string& scene_file) {
  const char* dir = std::getenv("COSIM_SCENE_DIR");
  const char* copy = std::getenv("COSIM_SCENE_COPY");
  std::error_code ec;
  if (dir && *dir && copy && std::filesystem::equivalent(scene_file, copy, ec)) return dir;
  return std::filesystem::path(scene_file).parent_path().string();
}

double coupled_end_time(Node& root) {
  // The coupler validates its section; here only a usable end time counts.
  const YAML::Node c = root.raw("coupling");
  if (!c || !c.IsMap() || !c["time"] || !c["time"].IsMap() || !c["time"]["end"]) return 0.0;
  try {
    const double end = c["time"]["end"].as<double>();
    return end > 0 ? end : 0.0;
  } catch (const YAML::Exception&) { return 0.0; }
}

std::vector<Node> Node::list(const std::string& key) {
  used_.insert(key);
  YAML::Node n = at(key);
  if (!n || n.IsNull()) fail(key, "a list, but the key is missing" + typo_of_missing(key));
  if (!n.IsSequence()) fail(key, "a list, got " + describe(n));
  return Node(n, key_path(key), ctx_).elements();
}

std::vector<Node> Node::elements() const {
  if (!node_.IsSequence()) fail("", "a list, got " + describe(node_));
  std::vector<Node> out;
  for (std::size_t i = 0; i < node_.size(); ++i) out.emplace_back(node_[i], path_ + "." + std::to_string(i), ctx_);
  return out;
}

std::string Node::typo_of_missing(const std::string& key) const {
  if (!node_.IsMap()) return "";
  // A key already asked for is valid, not a typo. A missing key is matched more strictly than an unknown one: a
  // short key (end, rho) is a few edits from most other short keys.
  const auto lower = [](std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
  };
  const std::size_t allowed = key.size() >= 4 ? 2 : key.size() >= 2 ? 1 : 0;
  std::size_t best_d = allowed + 1;
  std::string given;
  YAML::Mark mark = YAML::Mark::null_mark();
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    if (!it->first.IsScalar()) continue;
    const std::string k = it->first.Scalar();
    if (k == key || used_.count(k)) continue;
    const std::size_t d = lower(k) == lower(key) ? 0 : edit_distance(key, k);
    if (d < best_d) {
      best_d = d;
      given = k;
      mark = it->first.Mark();
    }
  }
  if (given.empty()) return "";
  if (ctx_->overridden.count(key_path(given)))
    return fmt::format(" (did you mean '{}', given with --set {}?)", given, key_path(given));
  if (mark.is_null()) return fmt::format(" (did you mean '{}'?)", given);
  return fmt::format(" (did you mean '{}', given at line {}?)", given, mark.line + 1);
}

void Node::finish() const {
  if (!node_.IsMap()) return;
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    std::string k = it->first.as<std::string>();
    if (used_.count(k)) continue;
    std::string best = closest(k, used_);
    std::string valid;
    for (const auto& u : used_) valid += (valid.empty() ? "" : ", ") + u;
    std::string kp = key_path(k);
    int line = it->first.Mark().is_null() ? 0 : it->first.Mark().line + 1;
    std::string loc = line > 0 ? fmt::format("{}:{}: {}", ctx_->file, line, kp) : where(k);
    throw ConfigError(fmt::format("{}: unknown key{}; valid keys here: {}", loc,
                                  best.empty() ? "" : fmt::format(" (did you mean '{}'?)", best),
                                  valid.empty() ? "(none)" : valid));
  }
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j)
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] == b[j - 1] ? 0u : 1u)});
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

std::string closest(const std::string& word, const std::set<std::string>& candidates) {
  std::string best;
  std::size_t best_d = std::max<std::size_t>(3, word.size() / 2) + 1;
  for (const auto& c : candidates) {
    std::size_t d = edit_distance(word, c);
    if (d < best_d) {
      best_d = d;
      best = c;
    }
  }
  return best;
}

Node load_file(const std::string& file, const std::vector<std::string>& overrides) {
  std::ifstream in(file);
  if (!in) throw ConfigError(fmt::format("{}: cannot open scene file", file));
  std::stringstream ss;
  ss << in.rdbuf();
  return load_string(ss.str(), scene_name(file), overrides);
}

std::string scene_name(const std::string& file) {
  // Under `cosim run` the solvers read the launcher's copy of the scene ($COSIM_SCENE_COPY), line for line the
  // user's file ($COSIM_SCENE_FILE).
  const char* copy = std::getenv("COSIM_SCENE_COPY");
  const char* given = std::getenv("COSIM_SCENE_FILE");
  std::error_code ec;
  if (copy && given && *given && std::filesystem::equivalent(file, copy, ec)) return given;
  return file;
}

namespace {
// A key given twice in one map is an error (yaml-cpp keeps the first, PyYAML the last: the scene would mean
// different things to our solvers and to Python tools); both lines are named.
void refuse_duplicate_keys(const YAML::Node& n, const std::string& name) {
  if (n.IsSequence())
    for (const auto& e : n) refuse_duplicate_keys(e, name);
  if (!n.IsMap()) return;
  std::map<std::string, int> first_line;
  for (const auto& kv : n) {
    if (kv.first.IsScalar()) {
      const std::string key = kv.first.Scalar();
      const int line = kv.first.Mark().line + 1;
      const auto [it, fresh] = first_line.emplace(key, line);
      if (!fresh)
        throw ConfigError(fmt::format("{}:{}: key '{}' is given twice (first at line {}); give each key once", name,
                                      line, key, it->second));
    }
    refuse_duplicate_keys(kv.second, name);
  }
}

// The line of a YAML syntax error, to say when a tab is the cause (YAML indents with spaces only).
std::string tab_hint(const std::string& text, int line) {
  std::istringstream in(text);
  std::string l;
  for (int i = 0; i <= line && std::getline(in, l); ++i) {}
  return l.find('\t') != std::string::npos ? " (the line contains a tab: YAML indents with spaces only)" : "";
}
}  // namespace

Node load_string(const std::string& text, const std::string& name, const std::vector<std::string>& overrides) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw ConfigError(fmt::format("{}:{}:{}: YAML syntax error: {}{}", name, e.mark.line + 1, e.mark.column + 1, e.msg,
                                  tab_hint(text, e.mark.line)));
  }
  refuse_duplicate_keys(root, name);
  return make_root(root, name, overrides);
}

}  // namespace cosim::config
