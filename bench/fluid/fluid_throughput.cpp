// Throughput of the fluid solver: cell-updates per second (one update = one full time step of
// one cell, all Runge-Kutta stages) and state memory per cell, for a scene and thread count.
// Usage: fluid_throughput SCENE.yaml [--steps N] [--threads T] [--after T_s] [--profile] [--set k=v ...]
// --after advances the scene to that time first, so the rate is measured on a developed flow.
// Roofline: the solver's bytes per cell-update from its passes (FluidSimulation::traffic_bytes_per_cell_update)
// against the STREAM triad a[i] = b[i] + s c[i] measured in the same run on the same threads (24 bytes per
// element, arrays of 128 MiB each, far beyond the caches, best of 5): the bandwidth ceiling is triad / bytes.
// --profile adds "passes": thread-nanoseconds per cell-update of each pass (pass_profile.h), from a second timed
// run of the same steps with the clocks on, so that the rate above is measured without them.
#include <fmt/format.h>
#include <omp.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <string>
#include <vector>

#include "fluid_solver/core/simulation.h"

namespace {

// Triad bandwidth [bytes/s] on the current OpenMP threads.
double triad_bandwidth() {
  const std::size_t n = std::size_t{1} << 24;
  std::vector<double> a(n), b(n, 1.0), c(n, 2.0);
  const long ln = static_cast<long>(n);
#pragma omp parallel for schedule(static)
  for (long i = 0; i < ln; ++i) a[static_cast<std::size_t>(i)] = 0.0;  // first touch on the threads that use it
  double best = 1e300;
  for (int rep = 0; rep < 5; ++rep) {
    const double s = 0.5 + rep;
    const auto t0 = std::chrono::steady_clock::now();
#pragma omp parallel for schedule(static)
    for (long i = 0; i < ln; ++i) {
      const auto k = static_cast<std::size_t>(i);
      a[k] = b[k] + s * c[k];
    }
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  if (a[n / 2] != b[n / 2] + 4.5 * c[n / 2]) return 0.0;  // the loop ran (and is not optimised away)
  return 24.0 * static_cast<double>(n) / best;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"fluid solver throughput benchmark"};
  std::string scene_file;
  int steps = 20, threads = 1;
  double after = 0.0;
  bool profile = false;
  std::vector<std::string> sets;
  app.add_option("scene", scene_file)->required();
  app.add_option("--steps", steps);
  app.add_option("--threads", threads);
  app.add_option("--set", sets);
  app.add_option("--after", after, "advance to this time (s) before timing");
  app.add_flag("--profile", profile, "time each pass of the step (a second run of the same steps)");
  CLI11_PARSE(app, argc, argv);
  auto scene = cosim::fluid::load_fluid_scene(scene_file, sets);
  scene.threads = threads;
  auto sim = cosim::fluid::make_simulation(scene);
  const double dt = sim->stable_dt();
  sim->advance(dt);  // warm-up
  for (double t = dt; t < after;) {
    const double step = sim->stable_dt();
    sim->advance(step);
    t += step;
  }
  const auto timed_steps = [&] {  // wall seconds of `steps` CFL steps
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < steps; ++i) sim->advance(sim->stable_dt());
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  const double wall = timed_steps();
  const double cells = static_cast<double>(sim->interior_cells());
  const double rate = steps * cells / wall, traffic = sim->traffic_bytes_per_cell_update();
  const double triad = triad_bandwidth(), ceiling = triad / traffic;
  std::string passes;
  if (profile) {
    sim->set_pass_profiling(true);
    const double pwall = timed_steps();
    const cosim::fluid::PassTimes pt = sim->pass_times();
    const double updates = steps * cells;
    passes = ", \"passes_ns_per_cell_update\": {";
    for (int p = 0; p < cosim::fluid::kPassCount; ++p)
      passes += fmt::format("\"{}\": {:.2f}, ", cosim::fluid::kPassNames[p], 1e9 * pt.seconds[p] / updates);
    passes += fmt::format("\"wall_times_threads\": {:.2f}}}", 1e9 * pwall * omp_get_max_threads() / updates);
  }
  fmt::print(
      "{{\"scene\": \"{}\", \"cells\": {}, \"phases\": {}, \"threads\": {}, \"steps\": {}, \"wall_s\": {:.4f}, "
      "\"cell_updates_per_s\": {:.6e}, \"bytes_per_cell\": {:.1f}, \"traffic_bytes_per_cell_update\": {:.0f}, "
      "\"triad_bytes_per_s\": {:.4e}, \"ceiling_cell_updates_per_s\": {:.4e}, \"fraction_of_ceiling\": {:.3f}{}}}\n",
      scene.name, cells, scene.num_phases(), omp_get_max_threads(), steps, wall, rate,
      static_cast<double>(sim->state_bytes()) / cells, traffic, triad, ceiling, rate / ceiling, passes);
}
