// The C interface's handle: creating it, its settings (one by one or from the solver's command line), the
// handshake and closing.
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>

#include "client/handle.h"
#include "common/config/config.h"
#include "common/coupling/scene_hash.h"
#include "common/coupling/wire.h"

using namespace cosim;
using client_detail::guarded;

namespace {
std::string str(const char* s, const char* what) {
  if (!s) throw std::invalid_argument(std::string(what) + ": null string");
  return s;
}
// The scene hash; an unreadable scene file is a scene error (COSIM_E_SCENE).
std::string hash_of(const std::string& file, const std::vector<std::string>& overrides) {
  try {
    return coupling::scene_hash(file, overrides);
  } catch (const coupling::CouplingError& e) { throw config::ConfigError(e.what()); }
}
int with(cosim_client* c, const std::function<void(cosim_client&)>& f) {
  return guarded([&] {
    if (!c) throw std::invalid_argument("null cosim_client handle");
    if (c->client) throw std::logic_error("already connected: settings go before cosim_hello()");
    f(*c);
  });
}
}  // namespace

extern "C" {

const char* cosim_library_version(void) { return COSIM_CLIENT_VERSION; }
int cosim_protocol_version(void) { return static_cast<int>(coupling::kProtocolVersion); }

int cosim_scene_hash(const char* scene_file, const char* const* overrides, int n_overrides, char out[17]) {
  return guarded([&] {
    if (!out || n_overrides < 0 || (n_overrides > 0 && !overrides)) throw std::invalid_argument("cosim_scene_hash");
    std::vector<std::string> o;
    for (int i = 0; i < n_overrides; ++i) o.push_back(str(overrides[i], "override"));
    const std::string h = hash_of(str(scene_file, "scene file"), o);
    std::memcpy(out, h.c_str(), 17);
  });
}

int cosim_create(cosim_client** out, int role) {
  return guarded([&] {
    if (!out) throw std::invalid_argument("cosim_create: null output");
    *out = nullptr;
    if (role != COSIM_ROLE_FLUID && role != COSIM_ROLE_SOLID)
      throw std::invalid_argument("cosim_create: role " + std::to_string(role) +
                                  ", expected COSIM_ROLE_FLUID or COSIM_ROLE_SOLID");
    auto c = std::make_unique<cosim_client>();
    c->options.role = role == COSIM_ROLE_FLUID ? coupling::Role::Fluid : coupling::Role::Solid;
    c->options.program = role == COSIM_ROLE_FLUID ? "fluid client" : "solid client";
    *out = c.release();
  });
}

int cosim_parse_args(cosim_client* c, int argc, char** argv) {
  return with(c, [&](cosim_client& h) {
    for (int i = 1; i < argc; ++i) {
      const std::string a = str(argv[i], "argument");
      const bool takes_value = a == "--out" || a == "--coupler" || a == "--token" || a == "--set" || a == "--restart";
      if (takes_value && i + 1 >= argc) throw std::invalid_argument(a + ": expected a value");
      if (a == "--out") h.out_dir = str(argv[++i], a.c_str());
      else if (a == "--coupler") h.options.endpoint = str(argv[++i], a.c_str());
      else if (a == "--token") h.options.token = str(argv[++i], a.c_str()), h.token_given = true;
      else if (a == "--set") h.overrides.push_back(str(argv[++i], a.c_str()));
      else if (a == "--restart") h.restart_set = str(argv[++i], a.c_str());
      else if (!a.starts_with("-") && h.scene_file.empty()) h.scene_file = a;
      else
        throw std::invalid_argument("unexpected argument '" + a +
                                    "' (expected SCENE --out DIR --coupler ENDPOINT [--token T] [--set k=v]... "
                                    "[--restart SET])");
    }
    h.scene.reset();
  });
}

int cosim_set_endpoint(cosim_client* c, const char* e) {
  return with(c, [&](cosim_client& h) { h.options.endpoint = str(e, "endpoint"); });
}
int cosim_set_token(cosim_client* c, const char* t) {
  return with(c, [&](cosim_client& h) {
    h.options.token = str(t, "token");
    h.token_given = true;
  });
}
int cosim_set_scene(cosim_client* c, const char* f) {
  return with(c, [&](cosim_client& h) {
    h.scene_file = str(f, "scene file");
    h.scene.reset();
  });
}
int cosim_add_override(cosim_client* c, const char* a) {
  return with(c, [&](cosim_client& h) {
    h.overrides.push_back(str(a, "override"));
    h.scene.reset();
  });
}
int cosim_set_scene_hash(cosim_client* c, const char* hash) {
  return with(c, [&](cosim_client& h) { h.options.scene_hash = str(hash, "scene hash"); });
}
int cosim_set_program(cosim_client* c, const char* name) {
  return with(c, [&](cosim_client& h) { h.options.program = str(name, "program"); });
}
int cosim_add_phase(cosim_client* c, const char* name, double min_pressure) {
  return with(c, [&](cosim_client& h) {
    h.options.phase_names.push_back(str(name, "phase name"));
    h.options.phase_min_pressure.push_back(min_pressure);
  });
}
int cosim_set_restart(cosim_client* c, long long cycle, double time) {
  return with(c, [&](cosim_client& h) {
    if (cycle < 0) throw std::invalid_argument("cosim_set_restart: negative cycle");
    h.options.restarted_from = static_cast<long>(cycle);
    h.options.restart_time = time;
  });
}
int cosim_set_ranks(cosim_client* c, int ranks) {
  return with(c, [&](cosim_client& h) {
    if (ranks < 1 || static_cast<unsigned>(ranks) > coupling::kMaxHelloRanks)
      throw std::invalid_argument("cosim_set_ranks: " + std::to_string(ranks) + ", expected 1 to " +
                                  std::to_string(coupling::kMaxHelloRanks) + " MPI ranks");
    h.options.ranks = static_cast<std::uint32_t>(ranks);
  });
}
int cosim_set_connect_timeout(cosim_client* c, double seconds) {
  return with(c, [&](cosim_client& h) {
    if (!(seconds > 0)) throw std::invalid_argument("cosim_set_connect_timeout: expected seconds > 0");
    h.options.connect_timeout = seconds;
  });
}

const char* cosim_scene_file(const cosim_client* c) { return c ? c->scene_file.c_str() : ""; }
const char* cosim_out_dir(const cosim_client* c) { return c ? c->out_dir.c_str() : ""; }
const char* cosim_restart_set(const cosim_client* c) { return c ? c->restart_set.c_str() : ""; }

int cosim_hello(cosim_client* c) {
  return with(c, [&](cosim_client& h) {
    if (h.options.endpoint.empty()) throw std::invalid_argument("no coupler endpoint (--coupler)");
    if (!h.token_given) {
      const char* t = std::getenv("COSIM_TOKEN");
      h.options.token = t ? t : "";
    }
    if (h.options.scene_hash.empty()) {
      if (h.scene_file.empty()) throw std::invalid_argument("no scene file and no scene hash");
      h.options.scene_hash = hash_of(h.scene_file, h.overrides);
    }
    h.client = std::make_unique<coupling::Client>(h.options);
  });
}

void cosim_close(cosim_client* c) {
  if (!c) return;
  if (c->client) c->client->close();
  delete c;
}

}  // extern "C"
