#include "common/coupling/wire.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "common/coupling/errors.h"

namespace cosim::coupling {

const char* role_name(Role r) {
  switch (r) {
    case Role::Coupler: return "coupler";
    case Role::Fluid: return "fluid";
    case Role::Solid: return "solid";
  }
  return "?";
}

const char* mode_name(Mode m) {
  switch (m) {
    case Mode::Impedance: return "impedance";
    case Mode::Standard: return "standard";
    case Mode::Characteristic: return "characteristic";
    case Mode::Robin: return "robin";
  }
  return "?";
}

const char* scheme_name(Scheme s) { return s == Scheme::Sequential ? "sequential" : "pipelined"; }

pb::CouplingScheme to_pb(Scheme s) {
  return s == Scheme::Sequential ? pb::COUPLING_SCHEME_SEQUENTIAL : pb::COUPLING_SCHEME_PIPELINED;
}

Scheme from_pb(pb::CouplingScheme s) {
  return s == pb::COUPLING_SCHEME_SEQUENTIAL ? Scheme::Sequential : Scheme::Pipelined;
}

pb::Role to_pb(Role r) {
  switch (r) {
    case Role::Coupler: return pb::ROLE_COUPLER;
    case Role::Fluid: return pb::ROLE_FLUID;
    case Role::Solid: return pb::ROLE_SOLID;
  }
  return pb::ROLE_UNSPECIFIED;
}

Role from_pb(pb::Role r) {
  switch (r) {
    case pb::ROLE_COUPLER: return Role::Coupler;
    case pb::ROLE_FLUID: return Role::Fluid;
    case pb::ROLE_SOLID: return Role::Solid;
    default: throw ProtocolError(fmt::format("Header.sender: unknown role {}", static_cast<int>(r)));
  }
}

pb::CouplingMode to_pb(Mode m) {
  switch (m) {
    case Mode::Impedance: return pb::COUPLING_MODE_IMPEDANCE;
    case Mode::Standard: return pb::COUPLING_MODE_STANDARD;
    case Mode::Characteristic: return pb::COUPLING_MODE_CHARACTERISTIC;
    case Mode::Robin: return pb::COUPLING_MODE_ROBIN;
  }
  return pb::COUPLING_MODE_UNSPECIFIED;
}

Mode from_pb(pb::CouplingMode m) {
  switch (m) {
    case pb::COUPLING_MODE_STANDARD: return Mode::Standard;
    case pb::COUPLING_MODE_CHARACTERISTIC: return Mode::Characteristic;
    case pb::COUPLING_MODE_ROBIN: return Mode::Robin;
    default: return Mode::Impedance;
  }
}

std::string body_name(const pb::Envelope& e) { return body_name(e.body_case()); }

std::string body_name(pb::Envelope::BodyCase c) {
  switch (c) {
    case pb::Envelope::kHello: return "Hello";
    case pb::Envelope::kWelcome: return "Welcome";
    case pb::Envelope::kFaces: return "InterfaceFaces";
    case pb::Envelope::kSamples: return "FluidSamples";
    case pb::Envelope::kStates: return "InterfaceStates";
    case pb::Envelope::kDtProposal: return "DtProposal";
    case pb::Envelope::kDtDecision: return "DtDecision";
    case pb::Envelope::kOutputRequest: return "OutputRequest";
    case pb::Envelope::kStop: return "Stop";
    case pb::Envelope::kError: return "Error";
    case pb::Envelope::kHeartbeat: return "Heartbeat";
    case pb::Envelope::kCheckpointRequest: return "CheckpointRequest";
    case pb::Envelope::kCheckpointWritten: return "CheckpointWritten";
    case pb::Envelope::BODY_NOT_SET: return "(empty)";
  }
  return "(unknown)";
}

pb::Envelope make_envelope(Role sender, const std::string& token, long cycle, double time, double busy) {
  pb::Envelope e;
  auto* h = e.mutable_header();
  h->set_protocol_version(kProtocolVersion);
  h->set_cycle(cycle);
  h->set_time(time);
  h->set_sender(to_pb(sender));
  h->set_token(token);
  h->set_busy_seconds(busy);
  return e;
}

std::string encode(const pb::Envelope& e) { return e.SerializeAsString(); }

std::optional<pb::Envelope> decode(const std::string& bytes, std::string& why) {
  pb::Envelope e;
  if (!e.ParseFromString(bytes)) {
    why = fmt::format("malformed message ({} bytes): not a cosim Envelope", bytes.size());
    return std::nullopt;
  }
  if (!e.has_header()) {
    why = fmt::format("malformed message ({} bytes): Envelope.header missing", bytes.size());
    return std::nullopt;
  }
  if (e.body_case() == pb::Envelope::BODY_NOT_SET) {
    why = fmt::format("malformed message ({} bytes): Envelope has no body", bytes.size());
    return std::nullopt;
  }
  return e;
}

namespace {

// "Msg.field: n values, expected what = m" or "".
std::string size_check(const char* msg, const char* field, int n, long expected, const char* what) {
  if (n == expected) return "";
  return fmt::format("{}.{}: {} values, expected {} = {}", msg, field, n, what, expected);
}

template <class R>
std::string finite_check(const char* msg, const char* field, const R& values, bool allow_inf = false) {
  for (int i = 0; i < values.size(); ++i) {
    const double v = values[i];
    if (std::isnan(v) || (!allow_inf && std::isinf(v)))
      return fmt::format("{}.{}[{}]: {} is not a finite number", msg, field, i, v);
  }
  return "";
}

template <class R>
std::string nonnegative_check(const char* msg, const char* field, const R& values) {
  for (int i = 0; i < values.size(); ++i)
    if (values[i] < 0.0) return fmt::format("{}.{}[{}]: {}, expected >= 0", msg, field, i, values[i]);
  return "";
}

std::string first(std::initializer_list<std::string> errors) {
  for (const auto& e : errors)
    if (!e.empty()) return e;
  return "";
}

// The normal must point the way the face's vertices say (docs/protocol.md: 2D segment a -> b has the outward
// normal (b_y - a_y, a_x - b_x); a 3D triangle or quad by the right-hand rule): a flipped normal turns the load
// and the fluid's side of the wall around. Faces without a vertex orientation (1D points, degenerate faces)
// are not checked.
std::string orientation_check(const pb::InterfaceFaces& m) {
  const long n = m.count(), d = m.dim(), k = m.nodes_per_face();
  if (!((d == 2 && k == 2) || (d == 3 && (k == 3 || k == 4)))) return "";
  const auto x = [&](long f, int q, int c) { return m.vertex_position(m.face_vertex(f * k + q) * d + c); };
  for (long f = 0; f < n; ++f) {
    double g[3] = {0, 0, 0};
    if (d == 2) {
      g[0] = x(f, 1, 1) - x(f, 0, 1);
      g[1] = x(f, 0, 0) - x(f, 1, 0);
    } else {
      double d1[3], d2[3];  // quad: its diagonals 0 -> 2 and 1 -> 3; triangle: the edges 0 -> 1 and 0 -> 2
      for (int i = 0; i < 3; ++i) {
        d1[i] = k == 4 ? x(f, 2, i) - x(f, 0, i) : x(f, 1, i) - x(f, 0, i);
        d2[i] = k == 4 ? x(f, 3, i) - x(f, 1, i) : x(f, 2, i) - x(f, 0, i);
      }
      g[0] = d1[1] * d2[2] - d1[2] * d2[1];
      g[1] = d1[2] * d2[0] - d1[0] * d2[2];
      g[2] = d1[0] * d2[1] - d1[1] * d2[0];
    }
    double gn = 0, gg = 0;
    for (long c = 0; c < d; ++c) {
      gn += g[c] * m.normal(f * d + c);
      gg += g[c] * g[c];
    }
    if (!(gg > 0)) continue;
    if (gn < 0.5 * std::sqrt(gg))
      return fmt::format(
          "InterfaceFaces.normal[{}..{}]: face {} has a normal at {:.0f} degrees from the one its vertices give "
          "(face_vertex order), expected the outward normal of docs/protocol.md (flipped normals?)",
          f * d, f * d + d - 1, f, std::acos(std::clamp(gn / std::sqrt(gg), -1.0, 1.0)) * 180.0 / M_PI);
  }
  return "";
}

std::string validate_faces(const pb::InterfaceFaces& m) {
  if (m.dim() < 1 || m.dim() > 3) return fmt::format("InterfaceFaces.dim: {}, expected 1, 2 or 3", m.dim());
  const long n = m.count(), d = m.dim();
  std::string e =
      first({size_check("InterfaceFaces", "centre", m.centre_size(), n * d, "dim * count"),
             size_check("InterfaceFaces", "normal", m.normal_size(), n * d, "dim * count"),
             size_check("InterfaceFaces", "area", m.area_size(), n, "count"),
             size_check("InterfaceFaces", "velocity", m.velocity_size(), n * d, "dim * count"),
             size_check("InterfaceFaces", "normal_stress", m.normal_stress_size(), n, "count"),
             size_check("InterfaceFaces", "impedance", m.impedance_size(), n, "count"),
             finite_check("InterfaceFaces", "centre", m.centre()), finite_check("InterfaceFaces", "normal", m.normal()),
             finite_check("InterfaceFaces", "area", m.area()), finite_check("InterfaceFaces", "velocity", m.velocity()),
             finite_check("InterfaceFaces", "normal_stress", m.normal_stress()),
             finite_check("InterfaceFaces", "impedance", m.impedance(), true)});
  if (!e.empty()) return e;
  for (int i = 0; i < m.impedance_size(); ++i)
    if (!(m.impedance(i) > 0)) return fmt::format("InterfaceFaces.impedance[{}]: {}, expected > 0", i, m.impedance(i));
  // Physics of the geometry: a face has a positive area and a unit normal.
  for (long f = 0; f < n; ++f) {
    if (!(m.area(f) > 0)) return fmt::format("InterfaceFaces.area[{}]: {}, expected > 0 (face {})", f, m.area(f), f);
    double len2 = 0;
    for (long k = 0; k < d; ++k) len2 += m.normal(f * d + k) * m.normal(f * d + k);
    if (std::abs(std::sqrt(len2) - 1.0) > 1e-6)
      return fmt::format("InterfaceFaces.normal[{}..{}]: length {}, expected a unit normal (face {})", f * d,
                         f * d + d - 1, std::sqrt(len2), f);
  }
  if (m.nodes_per_face() != 0) {
    if (m.vertex_position_size() % d != 0)
      return fmt::format("InterfaceFaces.vertex_position: {} values, not a multiple of dim = {}",
                         m.vertex_position_size(), d);
    e = size_check("InterfaceFaces", "face_vertex", m.face_vertex_size(), n * m.nodes_per_face(),
                   "nodes_per_face * count");
    if (!e.empty()) return e;
    const long nv = m.vertex_position_size() / d;
    for (int i = 0; i < m.face_vertex_size(); ++i)
      if (m.face_vertex(i) >= nv)
        return fmt::format("InterfaceFaces.face_vertex[{}]: {} out of range (vertices: {})", i, m.face_vertex(i), nv);
    e = orientation_check(m);
    if (!e.empty()) return e;
  }
  return "";
}

std::string validate_samples(const pb::FluidSamples& m) {
  if (m.phases() < 1) return "FluidSamples.phases: 0, expected >= 1";
  const long n = m.count(), np = n * m.phases();
  const std::string e =
      first({size_check("FluidSamples", "alpha", m.alpha_size(), np, "count * phases"),
             size_check("FluidSamples", "rho", m.rho_size(), np, "count * phases"),
             size_check("FluidSamples", "normal_velocity", m.normal_velocity_size(), np, "count * phases"),
             size_check("FluidSamples", "pressure", m.pressure_size(), np, "count * phases"),
             size_check("FluidSamples", "impedance", m.impedance_size(), np, "count * phases"),
             size_check("FluidSamples", "wetted", m.wetted_size(), n, "count"),
             finite_check("FluidSamples", "alpha", m.alpha()), finite_check("FluidSamples", "rho", m.rho()),
             finite_check("FluidSamples", "normal_velocity", m.normal_velocity()),
             finite_check("FluidSamples", "pressure", m.pressure()),
             finite_check("FluidSamples", "impedance", m.impedance())});
  if (!e.empty()) return e;
  // Physics of the states: volume fractions in [0, 1], densities and impedances not negative.
  for (long i = 0; i < np; ++i) {
    const long f = i / m.phases(), k = i % m.phases();
    if (m.alpha(i) < 0.0 || m.alpha(i) > 1.0 + 1e-12)
      return fmt::format("FluidSamples.alpha[{}]: {}, expected a volume fraction in [0, 1] (face {}, phase {})", i,
                         m.alpha(i), f, k);
    if (m.rho(i) < 0.0)
      return fmt::format("FluidSamples.rho[{}]: {}, expected a density >= 0 (face {}, phase {})", i, m.rho(i), f, k);
    if (m.impedance(i) < 0.0)
      return fmt::format("FluidSamples.impedance[{}]: {}, expected >= 0 (face {}, phase {})", i, m.impedance(i), f, k);
  }
  return "";
}

std::string validate_states(const pb::InterfaceStates& m) {
  const long n = m.count(), np = n * m.phases();
  const long nf = m.face_pressure_size() ? n : 0;
  return first({size_check("InterfaceStates", "pressure", m.pressure_size(), np, "count * phases"),
                size_check("InterfaceStates", "normal_velocity", m.normal_velocity_size(), np, "count * phases"),
                size_check("InterfaceStates", "face_pressure", m.face_pressure_size(), nf, "count"),
                size_check("InterfaceStates", "face_normal_velocity", m.face_normal_velocity_size(), nf, "count"),
                size_check("InterfaceStates", "face_wetted", m.face_wetted_size(), nf, "count"),
                m.face_impedance_size() ? size_check("InterfaceStates", "face_impedance", m.face_impedance_size(), nf,
                                                     "count (with face_pressure)")
                                        : std::string(),
                finite_check("InterfaceStates", "pressure", m.pressure()),
                finite_check("InterfaceStates", "normal_velocity", m.normal_velocity()),
                finite_check("InterfaceStates", "face_pressure", m.face_pressure()),
                finite_check("InterfaceStates", "face_normal_velocity", m.face_normal_velocity()),
                finite_check("InterfaceStates", "face_impedance", m.face_impedance()),
                nonnegative_check("InterfaceStates", "face_impedance", m.face_impedance())});
}

}  // namespace

std::string validate_sample_pressures(const pb::FluidSamples& m, const std::vector<double>& min_pressure,
                                      const std::vector<std::string>& phase_names) {
  const long np = static_cast<long>(m.phases());
  if (min_pressure.empty() || static_cast<long>(min_pressure.size()) != np) return "";
  for (long f = 0; f < static_cast<long>(m.count()); ++f) {
    if (f < m.wetted_size() && !m.wetted(f)) continue;  // no fluid there: nothing sampled
    for (long k = 0; k < np; ++k) {
      const long i = f * np + k;
      if (i < m.pressure_size() && m.pressure(i) < min_pressure[k])
        return fmt::format(
            "FluidSamples.pressure[{}]: {} Pa, below the lowest pressure phase '{}' admits ({} Pa, Hello.phase_min_"
            "pressure) (face {}, phase {})",
            i, m.pressure(i), k < static_cast<long>(phase_names.size()) ? phase_names[k] : std::to_string(k),
            min_pressure[k], f, k);
    }
  }
  return "";
}

std::string validate(const pb::Envelope& e) {
  switch (e.body_case()) {
    case pb::Envelope::kFaces: return validate_faces(e.faces());
    case pb::Envelope::kSamples: return validate_samples(e.samples());
    case pb::Envelope::kStates: return validate_states(e.states());
    case pb::Envelope::kDtProposal:
      if (!(e.dt_proposal().dt() > 0) || !std::isfinite(e.dt_proposal().dt()))
        return fmt::format("DtProposal.dt: {}, expected a finite number > 0", e.dt_proposal().dt());
      return "";
    case pb::Envelope::kDtDecision:
      if (!(e.dt_decision().dt() >= 0) || !std::isfinite(e.dt_decision().dt()))
        return fmt::format("DtDecision.dt: {}, expected a finite number >= 0", e.dt_decision().dt());
      return "";
    case pb::Envelope::kCheckpointRequest:
      if (e.checkpoint_request().directory().empty() || e.checkpoint_request().directory()[0] != '/')
        return fmt::format("CheckpointRequest.directory: '{}', expected an absolute path",
                           e.checkpoint_request().directory());
      return "";
    case pb::Envelope::kCheckpointWritten: {
      const std::string& part = e.checkpoint_written().part();
      if (part.empty() || part.find('/') != std::string::npos || part == "." || part == "..")
        return fmt::format("CheckpointWritten.part: '{}', expected a file name in the set directory", part);
      return "";
    }
    default: return "";
  }
}

namespace {
template <class T, class R>
std::vector<T> vec(const R& r) {
  return std::vector<T>(r.begin(), r.end());
}
template <class T, class R>
void put(const std::vector<T>& v, R* r) {
  r->Assign(v.begin(), v.end());
}
}  // namespace

void to_pb(const Faces& f, pb::InterfaceFaces& m) {
  m.set_dim(f.dim);
  m.set_count(f.count);
  put(f.centre, m.mutable_centre());
  put(f.normal, m.mutable_normal());
  put(f.area, m.mutable_area());
  put(f.velocity, m.mutable_velocity());
  put(f.normal_stress, m.mutable_normal_stress());
  put(f.impedance, m.mutable_impedance());
  m.set_nodes_per_face(f.nodes_per_face);
  put(f.vertex_position, m.mutable_vertex_position());
  put(f.face_vertex, m.mutable_face_vertex());
}

Faces from_pb(const pb::InterfaceFaces& m) {
  Faces f;
  f.dim = static_cast<int>(m.dim());
  f.count = static_cast<int>(m.count());
  f.centre = vec<double>(m.centre());
  f.normal = vec<double>(m.normal());
  f.area = vec<double>(m.area());
  f.velocity = vec<double>(m.velocity());
  f.normal_stress = vec<double>(m.normal_stress());
  f.impedance = vec<double>(m.impedance());
  f.nodes_per_face = static_cast<int>(m.nodes_per_face());
  f.vertex_position = vec<double>(m.vertex_position());
  f.face_vertex = vec<std::uint32_t>(m.face_vertex());
  return f;
}

void to_pb(const FluidSamples& s, pb::FluidSamples& m) {
  m.set_count(s.count);
  m.set_phases(s.phases);
  put(s.alpha, m.mutable_alpha());
  put(s.rho, m.mutable_rho());
  put(s.normal_velocity, m.mutable_normal_velocity());
  put(s.pressure, m.mutable_pressure());
  put(s.impedance, m.mutable_impedance());
  m.mutable_wetted()->Clear();
  for (char w : s.wetted) m.add_wetted(w != 0);
}

FluidSamples from_pb(const pb::FluidSamples& m) {
  FluidSamples s;
  s.count = static_cast<int>(m.count());
  s.phases = static_cast<int>(m.phases());
  s.alpha = vec<double>(m.alpha());
  s.rho = vec<double>(m.rho());
  s.normal_velocity = vec<double>(m.normal_velocity());
  s.pressure = vec<double>(m.pressure());
  s.impedance = vec<double>(m.impedance());
  s.wetted = vec<char>(m.wetted());
  return s;
}

void to_pb(const InterfaceStates& s, pb::InterfaceStates& m) {
  m.set_count(s.count);
  m.set_phases(s.phases);
  put(s.pressure, m.mutable_pressure());
  put(s.normal_velocity, m.mutable_normal_velocity());
  put(s.face_pressure, m.mutable_face_pressure());
  put(s.face_normal_velocity, m.mutable_face_normal_velocity());
  m.mutable_face_wetted()->Clear();
  for (char w : s.face_wetted) m.add_face_wetted(w != 0);
  put(s.face_impedance, m.mutable_face_impedance());
  m.set_mode(to_pb(s.mode));
}

InterfaceStates from_pb(const pb::InterfaceStates& m) {
  InterfaceStates s;
  s.count = static_cast<int>(m.count());
  s.phases = static_cast<int>(m.phases());
  s.pressure = vec<double>(m.pressure());
  s.normal_velocity = vec<double>(m.normal_velocity());
  s.face_pressure = vec<double>(m.face_pressure());
  s.face_normal_velocity = vec<double>(m.face_normal_velocity());
  s.face_wetted = vec<char>(m.face_wetted());
  s.face_impedance = vec<double>(m.face_impedance());
  s.mode = from_pb(m.mode());
  return s;
}

}  // namespace cosim::coupling
