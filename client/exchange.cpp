// The C interface's cycle: directives, faces, samples, states, step proposals, checkpoints, errors.
#include <cmath>
#include <limits>
#include <stdexcept>

#include "client/handle.h"

using namespace cosim;
using client_detail::connected;
using client_detail::copy_out;
using client_detail::guarded;

static_assert(static_cast<int>(coupling::Directive::Kind::Stop) == COSIM_STOP);
static_assert(static_cast<int>(coupling::Mode::Robin) == COSIM_MODE_ROBIN);
static_assert(static_cast<int>(coupling::Scheme::Sequential) == COSIM_SCHEME_SEQUENTIAL);

namespace {
// n values from p, or n copies of `fill` when p is null.
std::vector<double> values(const double* p, std::size_t n, double fill) {
  return p ? std::vector<double>(p, p + n) : std::vector<double>(n, fill);
}
std::vector<double> required(const double* p, std::size_t n, const char* what) {
  if (!p && n > 0) throw std::invalid_argument(std::string(what) + ": null array");
  return values(p, n, 0.0);
}
}  // namespace

extern "C" {

int cosim_next(cosim_client* c, cosim_directive* d) {
  return guarded([&] {
    if (!d) throw std::invalid_argument("cosim_next: null directive");
    c->directive = connected(c).next();
    const auto& r = c->directive;
    d->kind = static_cast<int>(r.kind);  // Advance, Output, Checkpoint, Stop: the COSIM_* order
    d->output_index = r.output_index;
    d->cycle = r.cycle;
    d->time = r.time;
    d->dt = r.dt;
  });
}
const char* cosim_stop_reason(const cosim_client* c) { return c ? c->directive.reason.c_str() : ""; }
const char* cosim_checkpoint_directory(const cosim_client* c) { return c ? c->directive.directory.c_str() : ""; }

int cosim_send_faces(cosim_client* c, int dim, int count, const double* centre, const double* normal,
                     const double* area, const double* velocity, const double* normal_stress, const double* impedance,
                     int nodes_per_face, int vertex_count, const double* vertex_position, const int* face_vertex) {
  return guarded([&] {
    auto& client = connected(c);
    if (dim < 1 || dim > 3 || count < 0 || nodes_per_face < 0 || vertex_count < 0)
      throw std::invalid_argument("cosim_send_faces: dim 1..3 and counts >= 0 expected");
    const auto n = static_cast<std::size_t>(count), nd = n * static_cast<std::size_t>(dim);
    coupling::Faces f;
    f.dim = dim;
    f.count = count;
    f.centre = required(centre, nd, "centre");
    f.normal = required(normal, nd, "normal");
    f.area = required(area, n, "area");
    f.velocity = values(velocity, nd, 0.0);
    f.normal_stress = values(normal_stress, n, 0.0);
    f.impedance = values(impedance, n, std::numeric_limits<double>::infinity());
    f.nodes_per_face = nodes_per_face;
    if (nodes_per_face > 0) {
      const auto nv = static_cast<std::size_t>(vertex_count), nfv = n * static_cast<std::size_t>(nodes_per_face);
      f.vertex_position = required(vertex_position, nv * static_cast<std::size_t>(dim), "vertex_position");
      if (!face_vertex && nfv > 0) throw std::invalid_argument("face_vertex: null array");
      for (std::size_t i = 0; i < nfv; ++i) {
        if (face_vertex[i] < 0 || face_vertex[i] >= vertex_count)
          throw std::invalid_argument("face_vertex: vertex " + std::to_string(face_vertex[i]) + " out of range");
        f.face_vertex.push_back(static_cast<std::uint32_t>(face_vertex[i]));
      }
    }
    client.send_faces(f);
  });
}

int cosim_receive_faces(cosim_client* c, int* dim, int* count, int* nodes_per_face, int* vertex_count) {
  return guarded([&] {
    c->faces = connected(c).receive_faces();
    const auto& f = c->faces;
    if (dim) *dim = f.dim;
    if (count) *count = f.count;
    if (nodes_per_face) *nodes_per_face = f.nodes_per_face;
    if (vertex_count) *vertex_count = f.dim > 0 ? static_cast<int>(f.vertex_position.size()) / f.dim : 0;
  });
}

int cosim_faces_get(const cosim_client* c, int field, double* out, int capacity, int* length) {
  if (!c) return client_detail::fail(COSIM_E_ARGUMENT, "null cosim_client handle");
  const auto& f = c->faces;
  switch (field) {
    case COSIM_FACE_CENTRE: return copy_out(f.centre, out, capacity, length);
    case COSIM_FACE_NORMAL: return copy_out(f.normal, out, capacity, length);
    case COSIM_FACE_AREA: return copy_out(f.area, out, capacity, length);
    case COSIM_FACE_VELOCITY: return copy_out(f.velocity, out, capacity, length);
    case COSIM_FACE_NORMAL_STRESS: return copy_out(f.normal_stress, out, capacity, length);
    case COSIM_FACE_IMPEDANCE: return copy_out(f.impedance, out, capacity, length);
    case COSIM_FACE_VERTEX_POSITION: return copy_out(f.vertex_position, out, capacity, length);
  }
  return client_detail::fail(COSIM_E_ARGUMENT, "cosim_faces_get: unknown field " + std::to_string(field));
}

int cosim_faces_vertices(const cosim_client* c, int* out, int capacity, int* length) {
  if (!c) return client_detail::fail(COSIM_E_ARGUMENT, "null cosim_client handle");
  const auto& fv = c->faces.face_vertex;
  const int n = static_cast<int>(fv.size());
  if (length) *length = n;
  if (n > capacity || (n > 0 && !out)) return client_detail::fail(COSIM_E_ARGUMENT, "cosim_faces_vertices: capacity");
  for (int i = 0; i < n; ++i) out[i] = static_cast<int>(fv[static_cast<std::size_t>(i)]);
  return COSIM_OK;
}

int cosim_send_samples(cosim_client* c, int count, int phases, const double* alpha, const double* rho,
                       const double* normal_velocity, const double* pressure, const double* impedance,
                       const int* wetted) {
  return guarded([&] {
    auto& client = connected(c);
    if (count < 0 || phases < 1) throw std::invalid_argument("cosim_send_samples: count >= 0, phases >= 1 expected");
    const auto n = static_cast<std::size_t>(count), np = n * static_cast<std::size_t>(phases);
    coupling::FluidSamples s;
    s.count = count;
    s.phases = phases;
    s.alpha = required(alpha, np, "alpha");
    s.rho = required(rho, np, "rho");
    s.normal_velocity = required(normal_velocity, np, "normal_velocity");
    s.pressure = required(pressure, np, "pressure");
    if (impedance) s.impedance = values(impedance, np, 0.0);
    if (!wetted && n > 0) throw std::invalid_argument("wetted: null array");
    for (std::size_t i = 0; i < n; ++i) s.wetted.push_back(wetted[i] ? 1 : 0);
    client.send_samples(s);
  });
}

int cosim_receive_states(cosim_client* c, int* count, int* phases) {
  return guarded([&] {
    c->states = connected(c).receive_states();
    if (count) *count = c->states.count;
    if (phases) *phases = c->states.phases;
  });
}

int cosim_states_get(const cosim_client* c, int field, double* out, int capacity, int* length) {
  if (!c) return client_detail::fail(COSIM_E_ARGUMENT, "null cosim_client handle");
  const auto& s = c->states;
  switch (field) {
    case COSIM_STATE_PRESSURE: return copy_out(s.pressure, out, capacity, length);
    case COSIM_STATE_NORMAL_VELOCITY: return copy_out(s.normal_velocity, out, capacity, length);
    case COSIM_STATE_FACE_PRESSURE: return copy_out(s.face_pressure, out, capacity, length);
    case COSIM_STATE_FACE_NORMAL_VELOCITY: return copy_out(s.face_normal_velocity, out, capacity, length);
    case COSIM_STATE_FACE_WETTED:
      return copy_out(std::vector<double>(s.face_wetted.begin(), s.face_wetted.end()), out, capacity, length);
    case COSIM_STATE_FACE_IMPEDANCE: {
      // Only mode robin carries impedances: zeros otherwise, one per face.
      const bool given = s.face_impedance.size() == s.face_pressure.size();
      return copy_out(given ? s.face_impedance : std::vector<double>(s.face_pressure.size(), 0.0), out, capacity,
                      length);
    }
  }
  return client_detail::fail(COSIM_E_ARGUMENT, "cosim_states_get: unknown field " + std::to_string(field));
}

int cosim_propose_dt(cosim_client* c, double dt) {
  return guarded([&] { connected(c).propose_dt(dt); });
}
int cosim_confirm_checkpoint(cosim_client* c, const char* part, long long bytes) {
  return guarded([&] {
    if (!part || bytes < 0) throw std::invalid_argument("cosim_confirm_checkpoint: part and bytes >= 0 expected");
    connected(c).confirm_checkpoint(part, static_cast<std::uint64_t>(bytes));
  });
}
int cosim_add_output_seconds(cosim_client* c, double seconds) {
  return guarded([&] { connected(c).add_output_seconds(seconds); });
}
void cosim_report_error(cosim_client* c, const char* reason) {
  if (c && c->client) c->client->report_error(reason ? reason : "unknown failure");
}
int cosim_check(const cosim_client* c) {
  return guarded([&] { connected(c).check(); });
}

int cosim_mode(const cosim_client* c) { return c && c->client ? static_cast<int>(c->client->mode()) : -1; }
int cosim_scheme(const cosim_client* c) { return c && c->client ? static_cast<int>(c->client->scheme()) : -1; }
long long cosim_cycle(const cosim_client* c) { return c && c->client ? c->client->cycle() : -1; }
double cosim_time(const cosim_client* c) { return c && c->client ? c->client->time() : 0.0; }
double cosim_timeout(const cosim_client* c) { return c && c->client ? c->client->timeout() : 0.0; }

}  // extern "C"
