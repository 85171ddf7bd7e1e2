// The C interface's scene queries: the scene file with its overrides applied, as the solvers read it
// (common/config), looked up by dotted key paths.
#include <sstream>
#include <stdexcept>

#include "client/handle.h"
#include "common/config/config.h"

using namespace cosim;
using client_detail::guarded;

namespace {

class NotFound : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The node at `key` ("a.b.0.c"); throws NotFound when a component is missing.
YAML::Node find(cosim_client* c, const char* key) {
  if (!c || !key) throw std::invalid_argument("null handle or key");
  if (!c->scene) {
    if (c->scene_file.empty()) throw std::logic_error("no scene file (cosim_set_scene or cosim_parse_args)");
    c->scene = YAML::Clone(config::load_file(c->scene_file, c->overrides).yaml());
  }
  YAML::Node cur = YAML::Clone(*c->scene);  // operator[] on a non-const node would add missing keys
  std::stringstream ss(key);
  for (std::string part; std::getline(ss, part, '.');) {
    YAML::Node next;
    if (cur.IsSequence()) {
      std::size_t idx = 0;
      try {
        idx = std::stoul(part);
      } catch (const std::exception&) { throw NotFound(std::string(key) + ": '" + part + "' is not a list index"); }
      if (idx >= cur.size()) throw NotFound(std::string(key) + ": no entry " + part);
      next = cur[idx];
    } else if (cur.IsMap() && cur[part]) {
      next = cur[part];
    } else {
      throw NotFound(std::string(key) + ": no key '" + part + "' in the scene");
    }
    cur.reset(next);
  }
  return cur;
}

int query(const std::function<void()>& f) {
  try {
    f();
    return COSIM_OK;
  } catch (const NotFound& e) { return client_detail::fail(COSIM_E_NOT_FOUND, e.what()); } catch (...) {
    return guarded([] { throw; });
  }
}

double number(const YAML::Node& n, const char* key) {
  if (!n.IsScalar()) throw config::ConfigError(std::string(key) + ": expected a number");
  try {
    return n.as<double>();
  } catch (const YAML::Exception&) {
    throw config::ConfigError(std::string(key) + ": '" + n.Scalar() + "' is not a number");
  }
}

}  // namespace

extern "C" {

int cosim_scene_has(cosim_client* c, const char* key, int* present) {
  if (present) *present = 0;
  const int rc = query([&] { find(c, key); });
  if (rc == COSIM_E_NOT_FOUND) return COSIM_OK;
  if (rc == COSIM_OK && present) *present = 1;
  return rc;
}

int cosim_scene_length(cosim_client* c, const char* key, int* length) {
  return query([&] {
    const YAML::Node n = find(c, key);
    if (!n.IsSequence() && !n.IsMap()) throw config::ConfigError(std::string(key) + ": expected a list or a section");
    if (length) *length = static_cast<int>(n.size());
  });
}

int cosim_scene_number(cosim_client* c, const char* key, double* value) {
  return query([&] {
    const double v = number(find(c, key), key);
    if (value) *value = v;
  });
}

int cosim_scene_numbers(cosim_client* c, const char* key, double* out, int capacity, int* length) {
  std::vector<double> v;
  const int rc = query([&] {
    const YAML::Node n = find(c, key);
    if (!n.IsSequence()) throw config::ConfigError(std::string(key) + ": expected a list of numbers");
    for (const auto& e : n) v.push_back(number(e, key));
  });
  return rc != COSIM_OK ? rc : client_detail::copy_out(v, out, capacity, length);
}

int cosim_scene_string(cosim_client* c, const char* key, const char** value) {
  return query([&] {
    const YAML::Node n = find(c, key);
    if (!n.IsScalar()) throw config::ConfigError(std::string(key) + ": expected a single value");
    c->text = n.Scalar();
    if (value) *value = c->text.c_str();
  });
}

}  // extern "C"
