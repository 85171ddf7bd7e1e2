// What a cosim_client handle of the C interface (include/cosim/client.h) holds, and how its functions turn
// exceptions into status codes. Internal to libcosim_client.
#pragma once

#include <yaml-cpp/yaml.h>

#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/coupling/client.h"
#include "cosim/client.h"

struct cosim_client {
  cosim::coupling::ClientOptions options;
  std::string scene_file, out_dir = ".", restart_set;
  std::vector<std::string> overrides;
  bool token_given = false;
  std::optional<YAML::Node> scene;  // loaded at the first scene query
  std::string text;                 // the last string returned by a scene query
  std::unique_ptr<cosim::coupling::Client> client;
  cosim::coupling::Directive directive;
  cosim::coupling::Faces faces;  // the last received
  cosim::coupling::InterfaceStates states;
};

namespace cosim::client_detail {

// A checkpoint set or part that does not match its manifest (COSIM_E_CORRUPT).
struct Corrupt : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Records `message` as this thread's last error and returns `code`.
int fail(int code, const std::string& message);
// Runs f() (returning void) and maps what it throws to a COSIM_E_* code.
int guarded(const std::function<void()>& f);
// The connected client, or throws std::logic_error (COSIM_E_ARGUMENT) before cosim_hello().
cosim::coupling::Client& connected(const cosim_client* c);
// Copies `values` into out[0..capacity); *length = values.size().
int copy_out(const std::vector<double>& values, double* out, int capacity, int* length);

}  // namespace cosim::client_detail
