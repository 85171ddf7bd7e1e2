// The cosim coupling client, C++ interface (docs/clients.md): header-only classes over the C interface
// (cosim/client.h), so libcosim_client keeps a C ABI and any C++ compiler can use it. Failures throw
// cosim::client::Error with the status code and the library's message.
//
//   cosim::client::Client c(cosim::client::Role::Solid, argc, argv);  // SCENE --out DIR --coupler EP ...
//   c.hello();
//   for (;;) {
//     const auto d = c.next();
//     if (d.kind == cosim::client::Kind::Stop) break;
//     ...  // docs/protocol.md "Writing a solver client"
//   }
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "cosim/client.h"

namespace cosim::client {

enum class Role { Fluid = COSIM_ROLE_FLUID, Solid = COSIM_ROLE_SOLID };
enum class Kind { Advance = COSIM_ADVANCE, Output = COSIM_OUTPUT, Checkpoint = COSIM_CHECKPOINT, Stop = COSIM_STOP };
enum class Mode {
  Impedance = COSIM_MODE_IMPEDANCE,
  Standard = COSIM_MODE_STANDARD,
  Characteristic = COSIM_MODE_CHARACTERISTIC,
  Robin = COSIM_MODE_ROBIN
};
enum class Scheme { Pipelined = COSIM_SCHEME_PIPELINED, Sequential = COSIM_SCHEME_SEQUENTIAL };

class Error : public std::runtime_error {
 public:
  Error(int code, const std::string& what) : std::runtime_error(what), code_(code) {}
  int code() const { return code_; }  // COSIM_E_*

 private:
  int code_;
};

// Throws Error for a status other than COSIM_OK.
inline void check(int status) {
  if (status != COSIM_OK) throw Error(status, cosim_last_error());
}

struct Directive {
  Kind kind = Kind::Stop;
  long long cycle = 0;
  double time = 0;        // t^n [s] (Output: the snapshot time)
  double dt = 0;          // Advance: the step [s]; 0 in cycle 0
  int output_index = 0;   // Output
  std::string reason;     // Stop
  std::string directory;  // Checkpoint: where this solver writes its part
};

// Solid -> coupler (send_faces) and coupler -> fluid (receive_faces). Empty velocity, normal_stress, impedance:
// 0, 0, +inf (rigid); nodes_per_face 0: no vertices.
struct Faces {
  int dim = 3;
  int count = 0;
  std::vector<double> centre, normal, area, velocity, normal_stress, impedance;
  int nodes_per_face = 0;
  std::vector<double> vertex_position;
  std::vector<int> face_vertex;
};

// Fluid -> coupler: count * phases each (impedance may stay empty); wetted: count.
struct Samples {
  int count = 0;
  int phases = 1;
  std::vector<double> alpha, rho, normal_velocity, pressure, impedance;
  std::vector<int> wetted;
};

// Coupler -> solvers. face_impedance: zeros outside mode robin.
struct States {
  int count = 0;
  int phases = 0;
  std::vector<double> pressure, normal_velocity;                                         // fluid: count * phases
  std::vector<double> face_pressure, face_normal_velocity, face_wetted, face_impedance;  // solid: count
};

// A checkpoint part as its set's manifest records it (verify_part).
struct PartRecord {
  long long bytes = 0;
  std::string sha256;   // 64 hex digits
  long long cycle = 0;  // the set's
  double time = 0;
};

// Checks `part` of the set directory `set` against its manifest (cosim_client_verify_part); Error with code
// COSIM_E_CORRUPT names the file and what differs.
inline PartRecord verify_part(const std::string& set, const std::string& part) {
  PartRecord r;
  char sha[65] = {0};
  check(cosim_client_verify_part(set.c_str(), part.c_str(), &r.bytes, sha, &r.cycle, &r.time));
  r.sha256 = sha;
  return r;
}

// The bytes of `part` of the set directory `set`, after the manifest's checks (cosim_read_part).
inline std::vector<unsigned char> read_part(const std::string& set, const std::string& part) {
  long long n = 0;
  std::vector<unsigned char> out(static_cast<std::size_t>(verify_part(set, part).bytes));
  check(cosim_read_part(set.c_str(), part.c_str(), out.data(), static_cast<long long>(out.size()), &n));
  return out;
}

class Client {
 public:
  explicit Client(Role role) { check(cosim_create(&c_, static_cast<int>(role))); }
  // With the solver's command line: SCENE --out DIR --coupler EP [--token T] [--set k=v]... [--restart SET].
  Client(Role role, int argc, char** argv) : Client(role) { check(cosim_parse_args(c_, argc, argv)); }
  ~Client() { cosim_close(c_); }
  Client(const Client&) = delete;
  Client& operator=(const Client&) = delete;

  // Settings, before hello(). No token: $COSIM_TOKEN; no scene hash: that of the scene file and overrides.
  void set_endpoint(const std::string& e) { check(cosim_set_endpoint(c_, e.c_str())); }
  void set_token(const std::string& t) { check(cosim_set_token(c_, t.c_str())); }
  void set_scene(const std::string& file) { check(cosim_set_scene(c_, file.c_str())); }
  void add_override(const std::string& assignment) { check(cosim_add_override(c_, assignment.c_str())); }
  void set_scene_hash(const std::string& h) { check(cosim_set_scene_hash(c_, h.c_str())); }
  void set_program(const std::string& name) { check(cosim_set_program(c_, name.c_str())); }
  void add_phase(const std::string& name, double min_pressure) {
    check(cosim_add_phase(c_, name.c_str(), min_pressure));
  }
  void set_restart(long long cycle, double time) { check(cosim_set_restart(c_, cycle, time)); }
  void set_connect_timeout(double seconds) { check(cosim_set_connect_timeout(c_, seconds)); }
  void set_ranks(int ranks) { check(cosim_set_ranks(c_, ranks)); }  // MPI ranks this connection speaks for
  std::string scene_file() const { return cosim_scene_file(c_); }
  std::string out_dir() const { return cosim_out_dir(c_); }
  std::string restart_set() const { return cosim_restart_set(c_); }

  // The scene with its overrides; keys like "solid.blocks.0.density".
  bool scene_has(const std::string& key) {
    int present = 0;
    check(cosim_scene_has(c_, key.c_str(), &present));
    return present != 0;
  }
  int scene_length(const std::string& key) {
    int n = 0;
    check(cosim_scene_length(c_, key.c_str(), &n));
    return n;
  }
  double scene_number(const std::string& key) {
    double v = 0;
    check(cosim_scene_number(c_, key.c_str(), &v));
    return v;
  }
  std::vector<double> scene_numbers(const std::string& key) {
    int n = 0;
    check(cosim_scene_length(c_, key.c_str(), &n));
    std::vector<double> v(static_cast<std::size_t>(n));
    check(cosim_scene_numbers(c_, key.c_str(), v.data(), n, &n));
    return v;
  }
  std::string scene_string(const std::string& key) {
    const char* s = nullptr;
    check(cosim_scene_string(c_, key.c_str(), &s));
    return s;
  }

  void hello() { check(cosim_hello(c_)); }

  Directive next() {
    cosim_directive d{};
    check(cosim_next(c_, &d));
    Directive r;
    r.kind = static_cast<Kind>(d.kind);
    r.cycle = d.cycle;
    r.time = d.time;
    r.dt = d.dt;
    r.output_index = d.output_index;
    if (r.kind == Kind::Stop) r.reason = cosim_stop_reason(c_);
    if (r.kind == Kind::Checkpoint) r.directory = cosim_checkpoint_directory(c_);
    return r;
  }

  void send_faces(const Faces& f) {
    check(cosim_send_faces(c_, f.dim, f.count, f.centre.data(), f.normal.data(), f.area.data(), opt(f.velocity),
                           opt(f.normal_stress), opt(f.impedance), f.nodes_per_face,
                           f.dim > 0 ? static_cast<int>(f.vertex_position.size()) / f.dim : 0, opt(f.vertex_position),
                           f.face_vertex.empty() ? nullptr : f.face_vertex.data()));
  }
  Faces receive_faces() {
    Faces f;
    int vertices = 0;
    check(cosim_receive_faces(c_, &f.dim, &f.count, &f.nodes_per_face, &vertices));
    f.centre = face_field(COSIM_FACE_CENTRE);
    f.normal = face_field(COSIM_FACE_NORMAL);
    f.area = face_field(COSIM_FACE_AREA);
    f.velocity = face_field(COSIM_FACE_VELOCITY);
    f.normal_stress = face_field(COSIM_FACE_NORMAL_STRESS);
    f.impedance = face_field(COSIM_FACE_IMPEDANCE);
    f.vertex_position = face_field(COSIM_FACE_VERTEX_POSITION);
    int n = 0;
    cosim_faces_vertices(c_, nullptr, 0, &n);
    f.face_vertex.resize(static_cast<std::size_t>(n));
    check(cosim_faces_vertices(c_, f.face_vertex.data(), n, &n));
    return f;
  }
  void send_samples(const Samples& s) {
    check(cosim_send_samples(c_, s.count, s.phases, s.alpha.data(), s.rho.data(), s.normal_velocity.data(),
                             s.pressure.data(), opt(s.impedance), s.wetted.data()));
  }
  States receive_states() {
    States s;
    check(cosim_receive_states(c_, &s.count, &s.phases));
    s.pressure = state_field(COSIM_STATE_PRESSURE);
    s.normal_velocity = state_field(COSIM_STATE_NORMAL_VELOCITY);
    s.face_pressure = state_field(COSIM_STATE_FACE_PRESSURE);
    s.face_normal_velocity = state_field(COSIM_STATE_FACE_NORMAL_VELOCITY);
    s.face_wetted = state_field(COSIM_STATE_FACE_WETTED);
    s.face_impedance = state_field(COSIM_STATE_FACE_IMPEDANCE);
    return s;
  }

  void propose_dt(double dt) { check(cosim_propose_dt(c_, dt)); }
  void confirm_checkpoint(const std::string& part, long long bytes) {
    check(cosim_confirm_checkpoint(c_, part.c_str(), bytes));
  }
  // Answers a Checkpoint directive: the part written with its digest file and confirmed (cosim_write_part).
  void write_part(const std::string& part, const void* data, long long bytes) {
    check(cosim_write_part(c_, part.c_str(), data, bytes));
  }
  void add_output_seconds(double s) { check(cosim_add_output_seconds(c_, s)); }
  void report_error(const std::string& reason) noexcept { cosim_report_error(c_, reason.c_str()); }
  void check_alive() const { check(cosim_check(c_)); }

  Mode mode() const { return static_cast<Mode>(cosim_mode(c_)); }
  Scheme scheme() const { return static_cast<Scheme>(cosim_scheme(c_)); }
  long long cycle() const { return cosim_cycle(c_); }
  double time() const { return cosim_time(c_); }
  double timeout() const { return cosim_timeout(c_); }
  cosim_client* handle() { return c_; }  // for calls of the C interface

 private:
  static const double* opt(const std::vector<double>& v) { return v.empty() ? nullptr : v.data(); }
  std::vector<double> face_field(int field) const {
    int n = 0;
    cosim_faces_get(c_, field, nullptr, 0, &n);
    std::vector<double> v(static_cast<std::size_t>(n));
    check(cosim_faces_get(c_, field, v.data(), n, &n));
    return v;
  }
  std::vector<double> state_field(int field) const {
    int n = 0;
    cosim_states_get(c_, field, nullptr, 0, &n);
    std::vector<double> v(static_cast<std::size_t>(n));
    check(cosim_states_get(c_, field, v.data(), n, &n));
    return v;
  }

  cosim_client* c_ = nullptr;
};

}  // namespace cosim::client
