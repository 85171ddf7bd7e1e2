// TEST HARNESS, not a solver: a protocol client that replays fixed data, so that the coupler, the launcher and
// the Python solid can be tested without the real solvers.
//   cosim_scripted_peer --role fluid|solid --endpoint EP [--token T] [--scene FILE] [--set k=v ...]
//                       [--protocol-version N] [--dt S] [--phases N] [--velocity V] [--impedance Z]
//                       [--pressure P] [--pressure-gradient G] [--connect-timeout S] [--out DIR]
//                       [--extra-proposals N] [--sample-delay-ms T] [--hang-after N] [--min-pressure P]
//                       [--faces N] [--ranks N]
// fluid: every face sees a fixed state per phase (alpha 1/phases, rho 1.2, u.n 0, p = P + G x_face, z = 408);
//        it proposes --dt each cycle.
// solid: two faces of a 1D slab between x = -1 and 0 (normals -x and +x, area 0.025 m^2) moving with the
//        fixed --velocity, impedance --impedance (inf: rigid); it proposes --dt each cycle, and with
//        --extra-proposals N sends N more DtProposals right after its faces (a misbehaving peer).
//        --faces N: instead, N square quads in 3D (side 0.01 m, area 1e-4 m^2, normal +x) in the plane x = x(t),
//        row by row in a grid of ceil(sqrt(N)) columns along y from (y, z) = (0, 0), with their vertices: an
//        interface of any size for benchmarks (the plane moves with --velocity along x).
//        --sample-delay-ms T makes the fluid wait T ms before each FluidSamples (a slow peer).
// --hang-after N: after N cycles it stops answering but keeps its heartbeats (a hung solver loop).
// Exit: 0 after a normal Stop, 5 on any coupling error (message on stderr), 2 for --faces with --role fluid.
#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <limits>
#include <optional>
#include <thread>

#include "common/app/run_options.h"
#include "common/coupling/client.h"
#include "common/coupling/scene_hash.h"

using namespace cosim::coupling;

namespace {
// The solid's faces of the default 1D slab between x = -1 + x and x (two faces).
Faces slab_faces(double x, double velocity, double impedance) {
  Faces f;
  f.dim = 2;
  f.count = 2;
  f.centre = {-1.0 + x, 0.0125, x, 0.0125};
  f.normal = {-1.0, 0.0, 1.0, 0.0};
  f.area = {0.025, 0.025};
  f.velocity = {velocity, 0.0, velocity, 0.0};
  f.normal_stress = {0.0, 0.0};
  f.impedance = {impedance, impedance};
  return f;
}

// --faces N: N quads of side h in the plane x, normal +x, columns along y, rows along z; the vertices of the
// whole grid (ny + 1 rows of nx + 1), each quad's counter-clockwise seen from +x (right-hand rule gives +x).
Faces grid_faces(int n, double x, double velocity, double impedance) {
  constexpr double h = 0.01;
  const int nx = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
  const int ny = (n + nx - 1) / nx;
  const auto un = static_cast<std::size_t>(n);
  Faces f;
  f.dim = 3;
  f.count = n;
  f.centre.resize(3 * un);
  f.normal.resize(3 * un);
  f.velocity.resize(3 * un);
  f.area.assign(un, h * h);
  f.normal_stress.assign(un, 0.0);
  f.impedance.assign(un, impedance);
  f.nodes_per_face = 4;
  f.face_vertex.resize(4 * un);
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) f.vertex_position.insert(f.vertex_position.end(), {x, i * h, j * h});
  for (int k = 0; k < n; ++k) {
    const int i = k % nx, j = k / nx;
    const std::size_t c = 3 * static_cast<std::size_t>(k);
    f.centre[c] = x;
    f.centre[c + 1] = (i + 0.5) * h;
    f.centre[c + 2] = (j + 0.5) * h;
    f.normal[c] = 1.0;
    f.velocity[c] = velocity;
    const auto v = [&](int a, int b) { return static_cast<std::uint32_t>(b * (nx + 1) + a); };
    const std::uint32_t q[4] = {v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)};
    std::copy(q, q + 4, f.face_vertex.begin() + 4 * static_cast<std::ptrdiff_t>(k));
  }
  return f;
}
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"scripted coupling peer (test harness)"};
  std::string role = "fluid", endpoint, token, scene, out;
  std::vector<std::string> overrides;
  unsigned version = 0;
  double dt = 1e-4, velocity = 1.0, impedance = std::numeric_limits<double>::infinity(), pressure = 1e5;
  int phases = 1;
  app.add_option("--role", role)->check(CLI::IsMember({"fluid", "solid"}));
  app.add_option("--endpoint,--coupler", endpoint, "coupler endpoint")->required();
  app.add_option("--token", token)->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  app.add_option("--scene,scene", scene);
  app.add_option("--set", overrides);
  app.add_option("--out", out);
  app.add_option("--protocol-version", version);
  std::uint32_t ranks = 1;
  app.add_option("--ranks", ranks, "Hello.ranks: the MPI ranks it claims to speak for (tests send absurd ones)");
  double connect_timeout = 30.0;
  app.add_option("--connect-timeout", connect_timeout, "seconds to wait for the Welcome");
  app.add_option("--dt", dt);
  app.add_option("--phases", phases);
  app.add_option("--velocity", velocity);
  app.add_option("--impedance", impedance);
  app.add_option("--pressure", pressure);
  std::optional<double> min_pressure;
  app.add_option("--min-pressure", min_pressure, "fluid: Hello.phase_min_pressure of every phase [Pa]");
  double gradient = 0.0;
  app.add_option("--pressure-gradient", gradient, "fluid: p = pressure + gradient * x_face [Pa/m]");
  int extra_proposals = 0;
  app.add_option("--extra-proposals", extra_proposals, "solid: DtProposals sent ahead of the cycle after its faces");
  long hang_after = -1;
  int sample_delay_ms = 0;
  app.add_option("--sample-delay-ms", sample_delay_ms, "fluid: wait this long before sending its samples");
  app.add_option("--hang-after", hang_after, "cycles after which it stops answering (heartbeats go on)");
  int faces = 0;
  app.add_option("--faces", faces, "solid: N quads in 3D instead of the 1D slab's two faces")
      ->check(CLI::Range(1, 100000000));
  CLI11_PARSE(app, argc, argv);
  if (faces > 0 && role != "solid") {
    std::cerr << "[scripted-" << role << "] error: --faces is an option of --role solid\n";
    return 2;
  }
  if (token.empty()) token = cosim::app::token_from_environment();  // as cosim run passes it
  const std::string tag = "[scripted-" + role + "] ";
  try {
    ClientOptions o;
    o.endpoint = endpoint;
    o.token = token;
    o.role = role == "fluid" ? Role::Fluid : Role::Solid;
    o.scene_hash = scene.empty() ? "" : scene_hash(scene, overrides);
    o.program = "scripted_" + role;
    o.protocol_version = version;
    o.ranks = ranks;
    o.connect_timeout = connect_timeout;
    for (int k = 0; k < phases; ++k) o.phase_names.push_back(fmt::format("phase{}", k));
    if (min_pressure) o.phase_min_pressure.assign(o.phase_names.size(), *min_pressure);
    if (o.role == Role::Solid) {
      o.phase_names.clear();
      o.phase_min_pressure.clear();
    }
    Client c(o);
    std::cerr << tag << "connected to " << endpoint << "\n";
    double x = 0.0;
    for (long cycle = 0;; ++cycle) {
      if (cycle == hang_after)
        for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));  // until a signal ends it
      const Directive d = c.next();
      if (d.kind == Directive::Kind::Stop) {
        std::cerr << tag << "stop: " << d.reason << "\n";
        return 0;
      }
      if (d.kind == Directive::Kind::Output) continue;
      if (o.role == Role::Solid) {
        x += velocity * d.dt;
        c.send_faces(faces > 0 ? grid_faces(faces, x, velocity, impedance) : slab_faces(x, velocity, impedance));
        for (int k = 0; k < extra_proposals; ++k) c.propose_dt(dt);
        c.receive_states();
      } else {
        const Faces f = c.receive_faces();
        FluidSamples s;
        s.count = f.count;
        s.phases = phases;
        for (int i = 0; i < f.count * phases; ++i) {
          s.alpha.push_back(1.0 / phases);
          s.rho.push_back(1.2);
          s.normal_velocity.push_back(0.0);
          s.pressure.push_back(pressure + gradient * f.centre[(i / phases) * f.dim]);
          s.impedance.push_back(408.0);
        }
        s.wetted.assign(f.count, 1);
        if (sample_delay_ms > 0) std::this_thread::sleep_for(std::chrono::milliseconds(sample_delay_ms));
        c.send_samples(s);
        c.receive_states();
      }
      c.propose_dt(dt);
    }
  } catch (const std::exception& e) {
    std::cerr << tag << "error: " << e.what() << "\n";
    return 5;
  }
}
