// Cost of the embedded boundary per cycle: a circle moving through a 512 x 512 background, two
// body sizes, against the same run without the body (measured side by side in one process).
// Prints a markdown table: the geometry time per cycle (clip, distance, categories, image points)
// as a fraction of the cycle. The solver-side work (ghost fill, mirrored wall faces) is O(ghost
// cells) and below the timing noise of a cycle on this machine.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <chrono>

#include "fluid_solver/core/embedded_bodies.h"
#include "fluid_solver/core/simulation.h"

using namespace cosim::fluid;

namespace {
std::string scene(int n, double radius, int segments) {
  std::string s = fmt::format(R"(
fluid:
  mesh: {{cells: [{0}, {0}], lower: [0.0, 0.0], upper: [1.0, 1.0]}}
  phases: [{{name: gas, eos: {{type: ideal_gas, gamma: 1.4}}}}]
  time: {{end: 1.0}}
  threads: 1
  initial:
    state: {{rho: 1.0, velocity: [0.5, 0.2], p: 1.0}}
)",
                              n);
  if (radius > 0)
    s += fmt::format("  embedded:\n    bodies:\n      - {{shape: circle, center: [0.45, 0.45], radius: {}, segments: {}, "
                     "velocity: [0.3, 0.1]}}\n",
                     radius, segments);
  return s;
}

double seconds_for(FluidSimulation& sim, int steps) {
  sim.advance(sim.stable_dt());  // warm-up
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < steps; ++i) sim.advance(sim.stable_dt());
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / steps;
}
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"embedded-boundary cost per cycle"};
  int n = 512, steps = 20;
  app.add_option("--cells", n);
  app.add_option("--steps", steps);
  CLI11_PARSE(app, argc, argv);
  auto plain = make_simulation(parse_fluid_scene(scene(n, 0, 0)));
  const double t_plain = seconds_for(*plain, steps);
  fmt::print("| body | faces | cut cells | ghost+solid-cut | cycle [ms] | geometry [ms] | geometry share |\n");
  fmt::print("|---|---|---|---|---|---|---|\n");
  fmt::print("| none | 0 | 0 | 0 | {:.2f} | - | - |\n", 1e3 * t_plain);
  for (double radius : {0.1, 0.3}) {
    const int segments = radius > 0.2 ? 1000 : 333;  // about the same face size
    auto sim = make_simulation(parse_fluid_scene(scene(n, radius, segments)));
    auto* run = dynamic_cast<EmbeddedBodiesRun<2>*>(sim.get());
    const double geo0 = run->geometry_seconds();
    const double t = seconds_for(*sim, steps);
    const double geo = (run->geometry_seconds() - geo0) / (steps + 1);
    std::size_t cut = 0;
    for (double k : sim->embedded_categories()) cut += (k == 1.0 || k == 2.0) ? 1 : 0;
    fmt::print("| circle R = {} | {} | {} | {} | {:.2f} | {:.2f} | {:.1f}% |\n", radius, segments, cut,
               sim->embedded().ghosts.size(), 1e3 * t, 1e3 * geo, 100 * geo / t);
  }
}
