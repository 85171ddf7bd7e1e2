// Helpers shared by the solid solver tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "solid_solver/core/simulation.h"

namespace cosim::solid::solid_test {

// Advances to time t with the solver's own step control (as the runner does).
inline void run_to(Simulation& sim, double t, long max_steps = 10000000) {
  while (sim.time() < t * (1.0 - 1e-14) && sim.steps() < max_steps) {
    double dt = sim.stable_dt();
    const double rem = t - sim.time();
    if (dt >= rem) dt = rem;
    else if (dt > 0.5 * rem) dt = 0.5 * rem;
    sim.advance(dt);
  }
}

// One hexahedron of edge 1 mm in uniaxial strain: symmetry planes everywhere except x_upper, which moves at
// -0.1 m/s (compression at 100 /s); the block `steel` with the given eos lines (indented 6) and J2 strength; no
// artificial viscosity.
inline SolidScene uniaxial_strain_scene(const std::string& eos_yaml, double G, double Y) {
  return parse_solid_scene(fmt::format(R"(
solid:
  mesh: {{cells: [1, 1, 1], lower: [0, 0, 0], upper: [0.001, 0.001, 0.001]}}
  blocks:
    - name: steel
      {}
      strength: {{shear_modulus: {}, yield_stress: {}}}
  boundaries:
    - {{set: x_lower, type: symmetry}}
    - {{set: x_upper, type: velocity, vx: -0.1}}
    - {{set: y_lower, type: symmetry}}
    - {{set: y_upper, type: symmetry}}
    - {{set: z_lower, type: symmetry}}
    - {{set: z_upper, type: symmetry}}
  numerics: {{q_quadratic: 0, q_linear: 0}}
  time: {{end: 1.0}}
)",
                                       eos_yaml, G, Y));
}

// Deterministic pseudo-random number in [-1, 1].
inline double hash_unit(int i, int k) {
  unsigned h = static_cast<unsigned>(i) * 2654435761u ^ static_cast<unsigned>(k + 17) * 40503u;
  h ^= h >> 13;
  h *= 0x5bd1e995u;
  h ^= h >> 15;
  return (h % 20001u) / 10000.0 - 1.0;
}

// Moves every node not on the box boundary by up to `frac` of the cell size h in each direction.
inline void distort_interior(Mesh& m, const std::array<double, 3>& lower, const std::array<double, 3>& upper, double h,
                             double frac) {
  for (int n = 0; n < m.num_nodes; ++n) {
    bool interior = true;
    for (int d = 0; d < m.dim; ++d) {
      const double x = m.x0[n * m.dim + d];
      interior = interior && std::abs(x - lower[d]) > 1e-12 && std::abs(x - upper[d]) > 1e-12;
    }
    if (!interior) continue;
    for (int d = 0; d < m.dim; ++d) m.x0[n * m.dim + d] += frac * h * hash_unit(n, d);
  }
}

// Radial density profile of a blast centred at the origin: elements binned by centroid radius (bin width h),
// bin-averaged density (rho0 where a bin is empty).
inline std::vector<double> radial_density(const Simulation& sim, double h, double rho0) {
  const Mesh& m = sim.mesh();
  const State& st = sim.state();
  std::vector<double> sum, cnt;
  for (int z = 0; z < m.num_elements; ++z) {
    const auto c = element_centroid(m, st.x, z);
    double r = 0;
    for (int d = 0; d < m.dim; ++d) r += c[d] * c[d];
    const std::size_t b = static_cast<std::size_t>(std::sqrt(r) / h);
    if (b >= sum.size()) {
      sum.resize(b + 1, 0.0);
      cnt.resize(b + 1, 0.0);
    }
    sum[b] += st.emass[z] / st.vol[z];
    cnt[b] += 1;
  }
  std::vector<double> rho(sum.size(), rho0);
  for (std::size_t b = 0; b < sum.size(); ++b)
    if (cnt[b] > 0) rho[b] = sum[b] / cnt[b];
  if (std::getenv("SOLID_TEST_PROFILE"))
    for (std::size_t b = 0; b < rho.size(); ++b) std::printf("  r %.4f rho %.4f n %g\n", (b + 0.5) * h, rho[b], cnt[b]);
  return rho;
}

// Shock radius = position of the density peak (the exact solution peaks at the shock), from a parabola
// through the largest bin and its neighbours.
inline double shock_radius_peak(const Simulation& sim, double h, double rho0) {
  const auto rho = radial_density(sim, h, rho0);
  std::size_t k = std::max_element(rho.begin(), rho.end()) - rho.begin();
  if (k == 0 || k + 1 >= rho.size()) return (k + 0.5) * h;
  const double a = rho[k - 1], b = rho[k], c = rho[k + 1];
  const double off = 0.5 * (a - c) / (a - 2 * b + c);
  return (k + 0.5 + off) * h;
}

// Radius where the density first reaches (rho0 + peak)/2 coming from outside (leading edge of the smeared
// front; on coarse meshes about one cell ahead of the peak).
inline double shock_radius_half_max(const Simulation& sim, double h, double rho0) {
  const auto rho = radial_density(sim, h, rho0);
  const double half = 0.5 * (rho0 + *std::max_element(rho.begin(), rho.end()));
  for (std::size_t b = rho.size() - 1; b > 0; --b)
    if (rho[b - 1] >= half && rho[b] < half) {
      const double f = (rho[b - 1] - half) / (rho[b - 1] - rho[b]);
      return h * (b - 0.5 + f);
    }
  return 0.0;
}

}  // namespace cosim::solid::solid_test
