// TEST HARNESS, not a solver: a protocol client that replays fixed data, so that the coupler, the launcher and
// the Python solid can be tested without the real solvers.
//   cosim_scripted_peer --role fluid|solid --endpoint EP [--token T] [--scene FILE] [--set k=v ...]
//                       [--protocol-version N] [--dt S] [--phases N] [--velocity V] [--impedance Z]
//                       [--pressure P] [--pressure-gradient G] [--connect-timeout S] [--out DIR]
//                       [--extra-proposals N] [--sample-delay-ms T] [--hang-after N] [--min-pressure P]
// fluid: every face sees a fixed state per phase (alpha 1/phases, rho 1.2, u.n 0, p = P + G x_face, z = 408);
//        it proposes --dt each cycle.
// solid: two faces of a 1D slab between x = -1 and 0 (normals -x and +x, area 0.025 m^2) moving with the
//        fixed --velocity, impedance --impedance (inf: rigid); it proposes --dt each cycle, and with
//        --extra-proposals N sends N more DtProposals right after its faces (a misbehaving peer).
//        --sample-delay-ms T makes the fluid wait T ms before each FluidSamples (a slow peer).
// --hang-after N: after N cycles it stops answering but keeps its heartbeats (a hung solver loop).
// Exit: 0 after a normal Stop, 5 on any coupling error (message on stderr).
#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <optional>
#include <thread>

#include "common/app/run_options.h"
#include "common/coupling/client.h"
#include "common/coupling/scene_hash.h"

using namespace cosim::coupling;

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
  CLI11_PARSE(app, argc, argv);
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
        Faces f;
        f.dim = 2;
        f.count = 2;
        f.centre = {-1.0 + x, 0.0125, x, 0.0125};
        f.normal = {-1.0, 0.0, 1.0, 0.0};
        f.area = {0.025, 0.025};
        f.velocity = {velocity, 0.0, velocity, 0.0};
        f.normal_stress = {0.0, 0.0};
        f.impedance = {impedance, impedance};
        c.send_faces(f);
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
