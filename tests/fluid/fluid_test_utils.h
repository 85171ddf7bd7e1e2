// Helpers shared by the fluid solver tests: build a scene from YAML text, run it, read fields.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "fluid_solver/core/simulation.h"

namespace cosim::fluid::test {

inline std::unique_ptr<FluidSimulation> run_scene(const std::string& yaml, const std::vector<std::string>& sets = {}) {
  FluidScene s = parse_fluid_scene(yaml, sets);
  auto sim = make_simulation(s);
  advance_to(*sim, s.t_end);
  return sim;
}

inline double l1_error(const std::vector<double>& a, const std::vector<double>& b) {
  double e = 0;
  for (std::size_t i = 0; i < a.size(); ++i) e += std::abs(a[i] - b[i]);
  return e / static_cast<double>(a.size());
}

inline std::vector<double> component(const std::vector<double>& v3, int d) {
  std::vector<double> out(v3.size() / 3);
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = v3[3 * i + d];
  return out;
}

inline double observed_order(double e_coarse, double e_fine, double ratio = 2.0) {
  return std::log(e_coarse / e_fine) / std::log(ratio);
}

// A 1D single-phase ideal-gas Riemann problem on [0,1] as a scene.
inline std::string riemann_scene(double rl, double ul, double pl, double rr, double ur, double pr, double x0,
                                 double t_end, int n, const std::string& numerics = "") {
  char buf[2048];
  std::snprintf(buf, sizeof(buf), R"(
name: riemann
fluid:
  mesh: {cells: [%d], lower: [0.0], upper: [1.0]}
  phases: [{name: gas, eos: {type: ideal_gas, gamma: 1.4}}]
  numerics: {%s}
  time: {end: %.17g}
  initial:
    state: {rho: %.17g, velocity: [%.17g], p: %.17g}
    regions:
      - half_space: {point: [%.17g], normal: [1.0]}
        state: {rho: %.17g, velocity: [%.17g], p: %.17g}
)",
                n, numerics.c_str(), t_end, rl, ul, pl, x0, rr, ur, pr);
  return buf;
}

}  // namespace cosim::fluid::test
