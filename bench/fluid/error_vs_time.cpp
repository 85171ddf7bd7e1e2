// Run time against error, side by side in one process: Sod (t = 0.2, L1 density error against
// the exact solution) and a smooth density wave (one period, L1 against exact cell averages),
// for AUFS, HLLC and Rusanov, first and second order, N from n_min doubling to n_max.
// Prints CSV: problem,flux,order,N,steps,wall_s,l1_rho
#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include <chrono>
#include <cmath>
#include <numbers>

#include "common/exact/exact_riemann.h"
#include "fluid_solver/core/simulation.h"

using namespace cosim;

namespace {
std::string scene_text(const std::string& problem, int n, const std::string& flux, const std::string& rec) {
  const std::string head = fmt::format(
      "fluid:\n  mesh: {{cells: [{}], lower: [0.0], upper: [1.0]}}\n  phases: [{{name: gas, eos: {{type: ideal_gas, "
      "gamma: 1.4}}}}]\n  numerics: {{flux: {}, reconstruction: {}}}\n  threads: 1\n",
      n, flux, rec);
  if (problem == "sod")
    return head +
           "  time: {end: 0.2}\n  initial:\n    state: {rho: 1.0, velocity: [0.0], p: 1.0}\n    regions:\n"
           "      - half_space: {point: [0.5], normal: [1.0]}\n        state: {rho: 0.125, velocity: [0.0], p: 0.1}\n";
  return head +
         "  time: {end: 1.0}\n  boundaries: {x_lower: periodic, x_upper: periodic}\n  initial:\n    profile: {type: "
         "density_wave, rho: 1.0, amplitude: 0.2, p: 1.0, wave_number: [1.0], velocity: [1.0]}\n";
}
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"fluid solver: error against run time"};
  int sod_min = 100, sod_max = 12800, wave_min = 16, wave_max = 2048;
  app.add_option("--sod-min", sod_min);
  app.add_option("--sod-max", sod_max);
  app.add_option("--wave-min", wave_min);
  app.add_option("--wave-max", wave_max);
  CLI11_PARSE(app, argc, argv);
  fmt::print("problem,flux,order,N,steps,wall_s,l1_rho\n");
  for (const std::string problem : {"sod", "wave"}) {
    const int nmin = problem == "sod" ? sod_min : wave_min, nmax = problem == "sod" ? sod_max : wave_max;
    for (const std::string flux : {"aufs", "hllc", "rusanov"})
      for (const std::string rec : {"first_order", "muscl"})
        for (int n = nmin; n <= nmax; n *= 2) {
          auto scene = fluid::parse_fluid_scene(scene_text(problem, n, flux, rec));
          auto sim = fluid::make_simulation(scene);
          std::vector<double> ref;
          if (problem == "wave") ref = sim->phase_fields(0).rho;  // exact cell averages after one period
          const auto t0 = std::chrono::steady_clock::now();
          fluid::advance_to(*sim, scene.t_end);
          const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
          const auto rho = sim->phase_fields(0).rho;
          if (problem == "sod") {
            exact::RiemannSolution ex({1, 0, 1}, {1.4, 0}, {0.125, 0, 0.1}, {1.4, 0});
            std::vector<double> u, p;
            exact::sample_on_cells(ex, 0.0, 1.0, n, 0.5, 0.2, ref, u, p);
          }
          double err = 0;
          for (int i = 0; i < n; ++i) err += std::abs(rho[i] - ref[i]);
          fmt::print("{},{},{},{},{},{:.6f},{:.6e}\n", problem, flux, rec == "muscl" ? 2 : 1, n, sim->steps(), wall,
                     err / n);
          std::fflush(stdout);
        }
  }
}
