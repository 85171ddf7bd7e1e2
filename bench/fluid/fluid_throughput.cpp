// Throughput of the fluid solver: cell-updates per second (one update = one full time step of
// one cell, all Runge-Kutta stages) and state memory per cell, for a scene and thread count.
// Usage: fluid_throughput SCENE.yaml [--steps N] [--threads T] [--after T_s] [--set k=v ...]
// --after advances the scene to that time first, so the rate is measured on a developed flow.
#include <fmt/format.h>
#include <omp.h>
#include <CLI/CLI.hpp>

#include <chrono>

#include "fluid_solver/core/simulation.h"

int main(int argc, char** argv) {
  CLI::App app{"fluid solver throughput benchmark"};
  std::string scene_file;
  int steps = 20, threads = 1;
  double after = 0.0;
  std::vector<std::string> sets;
  app.add_option("scene", scene_file)->required();
  app.add_option("--steps", steps);
  app.add_option("--threads", threads);
  app.add_option("--set", sets);
  app.add_option("--after", after, "advance to this time (s) before timing");
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
  auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < steps; ++i) sim->advance(sim->stable_dt());
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double cells = static_cast<double>(sim->interior_cells());
  fmt::print(
      "{{\"scene\": \"{}\", \"cells\": {}, \"phases\": {}, \"threads\": {}, \"steps\": {}, \"wall_s\": {:.4f}, "
      "\"cell_updates_per_s\": {:.6e}, \"bytes_per_cell\": {:.1f}}}\n",
      scene.name, cells, scene.num_phases(), omp_get_max_threads(), steps, wall, steps * cells / wall,
      static_cast<double>(sim->state_bytes()) / cells);
}
