// Validated reading of YAML scene files.
//
// Every value is read through a Node, which remembers the keys it was asked for. After a section
// has been read, finish() rejects any key nobody asked for and suggests the closest valid one.
// All errors are ConfigError with the message "file:line: key.path: what was expected".
// Command-line overrides (--set a.b.c=value) are applied to the YAML tree before reading; a value
// that came from an override is reported as "--set a.b.c" instead of a line number.
#pragma once

#include <yaml-cpp/yaml.h>

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace cosim::config {

class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Shared by all Nodes of one document.
struct DocumentContext {
  std::string file;
  std::set<std::string> overridden;  // key paths set with --set
};

// A range or set check applied to a value after conversion; returns an empty string when fine,
// otherwise the description of what was expected (e.g. "a number > 0").
template <class T>
using Check = std::function<std::string(const T&)>;

Check<double> positive();
Check<double> non_negative();
Check<double> in_range(double lo, double hi);        // lo <= v <= hi
Check<double> in_open_closed(double lo, double hi);  // lo <  v <= hi
Check<double> speed();                               // |v| <= 1e5 m/s: a velocity that makes physical sense
Check<int> int_at_least(int lo);
Check<std::string> one_of(std::vector<std::string> choices);

// `text` safe to quote in a message: every byte that is not printable ASCII or part of a printable UTF-8 character
// (control characters, invalid or overlong sequences) written as \xNN. is_printable: printable(text) == text.
std::string printable(const std::string& text);
bool is_printable(const std::string& text);

class Node {
 public:
  Node(YAML::Node node, std::string path, std::shared_ptr<DocumentContext> ctx);

  const std::string& path() const { return path_; }
  bool has(const std::string& key) const;
  bool is_map() const { return node_.IsMap(); }
  bool is_sequence() const { return node_.IsSequence(); }
  bool is_scalar() const { return node_.IsScalar(); }
  std::size_t size() const { return node_.size(); }

  template <class T>
  T get(const std::string& key, const T& fallback, Check<T> check = {});
  template <class T>
  T require(const std::string& key, Check<T> check = {});
  // The scalar value of this node itself (for list elements).
  template <class T>
  T as(Check<T> check = {}) const;

  // Fixed-size or bounded lists of numbers.
  std::vector<double> get_vector(const std::string& key, std::size_t min_len, std::size_t max_len,
                                 std::optional<std::vector<double>> fallback = std::nullopt, Check<double> check = {});

  Node child(const std::string& key);  // required map
  std::optional<Node> optional_child(const std::string& key);
  Node child_or_empty(const std::string& key);     // an empty map when missing
  std::vector<Node> list(const std::string& key);  // required sequence of entries
  std::vector<Node> elements() const;              // this node as a sequence

  // Mark a key as known without reading it (it belongs to another reader).
  void skip(const std::string& key) { used_.insert(key); }
  bool child_is_map(const std::string& key) const;

  // Reject keys that no get/require/child call asked for (with a suggestion for typos).
  void finish() const;

  // "file:line: path" prefix for messages about this node or one of its keys.
  std::string where(const std::string& key = "") const;
  // For a missing key: " (did you mean 'cell', given at line 7?)" when the section has a key that is not otherwise
  // valid and a typo away from it, else "".
  std::string typo_of_missing(const std::string& key) const;
  [[noreturn]] void fail(const std::string& key, const std::string& expected) const;

  // The raw YAML of a key (null when missing), for lenient reads of another reader's section.
  YAML::Node raw(const std::string& key) const { return at(key); }
  // This node's own YAML (the whole document for the root), for comparing two scenes.
  const YAML::Node& yaml() const { return node_; }

 private:
  YAML::Node at(const std::string& key) const;
  std::string key_path(const std::string& key) const;
  std::string describe(const YAML::Node& n) const;

  YAML::Node node_;
  std::string path_;
  std::shared_ptr<DocumentContext> ctx_;
  mutable std::set<std::string> used_;
};

// A point or vector of `dim` numbers under `key` (the other components 0); `fallback` when the key is absent.
std::array<double, 3> read_point(Node& n, const std::string& key, int dim,
                                 std::optional<std::vector<double>> fallback = std::nullopt, Check<double> check = {});

// Parse a YAML file, apply "a.b.c=value" overrides, return the root node.
Node load_file(const std::string& file, const std::vector<std::string>& overrides = {});
Node load_string(const std::string& text, const std::string& name = "<string>",
                 const std::vector<std::string>& overrides = {});

// A coupled scene (one with a coupling: section): its coupling.time.end [s], the end time the solvers'
// own (then optional) time.end defaults to; 0 for a standalone scene.
double coupled_end_time(Node& root);

// The directory that relative file names of a scene (a Gmsh mesh) are resolved against: $COSIM_SCENE_DIR when
// `scene_file` is $COSIM_SCENE_COPY (`cosim run` sets both: the solvers read a copy of the user's scene in the run
// directory, its names are relative to the user's), else the directory of `scene_file`.
std::string scene_base_dir(const std::string& scene_file);

// The name messages give a scene file: the file the user gave to `cosim run` ($COSIM_SCENE_FILE) when `file` is the
// launcher's copy of it ($COSIM_SCENE_COPY), else `file`.
std::string scene_name(const std::string& file);

// Levenshtein distance, for "did you mean" suggestions.
std::size_t edit_distance(const std::string& a, const std::string& b);
std::string closest(const std::string& word, const std::set<std::string>& candidates);

}  // namespace cosim::config

#include "common/config/config_impl.h"
