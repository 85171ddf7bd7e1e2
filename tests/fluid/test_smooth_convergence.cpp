// Smooth density wave advected once through a periodic box: observed order of MUSCL-RK2.
#include <gtest/gtest.h>

#include <numbers>

#include "fluid_test_utils.h"

namespace cosim::fluid::test {
namespace {

std::string wave_scene(int dim, int n, const std::string& limiter, double t_end) {
  std::string cells = "[", lo = "[", hi = "[", k = "[", per;
  for (int d = 0; d < dim; ++d) {
    cells += std::to_string(n) + (d + 1 < dim ? ", " : "]");
    lo += std::string("0.0") + (d + 1 < dim ? ", " : "]");
    hi += std::string("1.0") + (d + 1 < dim ? ", " : "]");
    k += std::string("1.0") + (d + 1 < dim ? ", " : "]");
    const char* ax[] = {"x", "y", "z"};
    per += std::string("    ") + ax[d] + "_lower: periodic\n    " + ax[d] + "_upper: periodic\n";
  }
  return "fluid:\n  mesh: {cells: " + cells + ", lower: " + lo + ", upper: " + hi +
         "}\n  phases: [{name: gas, eos: {type: ideal_gas, gamma: 1.4}}]\n  numerics: {limiter: " + limiter +
         "}\n  time: {end: " + std::to_string(t_end) + "}\n  boundaries:\n" + per +
         "  initial:\n    profile: {type: density_wave, rho: 1.0, "
         "amplitude: 0.2, p: 1.0, wave_number: " +
         k + ", velocity: " + k + "}\n";
}

// Exact cell average of rho = 1 + 0.2 sin(2 pi sum_d (x_d - t)) on the n^dim cells of [0,1]^dim.
std::vector<double> exact_wave(int dim, int n, double t) {
  const double h = 1.0 / n, w = 2.0 * std::numbers::pi;
  double damp = 1.0;
  for (int d = 0; d < dim; ++d) damp *= std::sin(0.5 * w * h) / (0.5 * w * h);
  std::vector<double> out;
  const int nj = dim > 1 ? n : 1, nk = dim > 2 ? n : 1;
  for (int k = 0; k < nk; ++k)
    for (int j = 0; j < nj; ++j)
      for (int i = 0; i < n; ++i) {
        double phase = (i + 0.5) * h - t;
        if (dim > 1) phase += (j + 0.5) * h - t;
        if (dim > 2) phase += (k + 0.5) * h - t;
        out.push_back(1.0 + 0.2 * std::sin(w * phase) * damp);
      }
  return out;
}

double wave_error(int dim, int n, const std::string& limiter, double t_end) {
  FluidScene s = parse_fluid_scene(wave_scene(dim, n, limiter, t_end));
  auto sim = make_simulation(s);
  advance_to(*sim, s.t_end);
  return l1_error(sim->phase_fields(0).rho, exact_wave(dim, n, t_end));
}

void check_order(int dim, int n0, const std::string& limiter, double min_order, double t_end = 1.0) {
  const double e1 = wave_error(dim, n0, limiter, t_end), e2 = wave_error(dim, 2 * n0, limiter, t_end),
               e3 = wave_error(dim, 4 * n0, limiter, t_end);
  std::printf("%dD density wave (%s): L1 %.3e %.3e %.3e, orders %.2f %.2f\n", dim, limiter.c_str(), e1, e2, e3,
              observed_order(e1, e2), observed_order(e2, e3));
  EXPECT_GE(observed_order(e2, e3), min_order);
  EXPECT_LT(e3, e1 / 8.0);
}

TEST(SmoothWave, SecondOrder1D) { check_order(1, 32, "van_leer", 1.8); }
TEST(SmoothWave, SecondOrder1DMinmodAndMC) {
  check_order(1, 32, "mc", 1.8);
  check_order(1, 64, "minmod", 1.6);  // minmod clips extrema hardest
}
TEST(SmoothWave, SecondOrder1DRk3) {
  // SSP-RK3 through --set: same spatial order, the time error no longer matters.
  const double e1 = [] {
    FluidScene s = parse_fluid_scene(wave_scene(1, 64, "van_leer", 1.0), {"fluid.time.integrator=rk3"});
    auto sim = make_simulation(s);
    advance_to(*sim, s.t_end);
    return l1_error(sim->phase_fields(0).rho, exact_wave(1, 64, 1.0));
  }();
  const double e2 = [] {
    FluidScene s = parse_fluid_scene(wave_scene(1, 128, "van_leer", 1.0), {"fluid.time.integrator=rk3"});
    auto sim = make_simulation(s);
    advance_to(*sim, s.t_end);
    return l1_error(sim->phase_fields(0).rho, exact_wave(1, 128, 1.0));
  }();
  std::printf("1D density wave RK3: L1 %.3e %.3e, order %.2f\n", e1, e2, observed_order(e1, e2));
  EXPECT_GE(observed_order(e1, e2), 1.8);
}
TEST(SmoothWave, SecondOrderDiagonal2D) { check_order(2, 32, "van_leer", 1.8); }
// 3D: a tenth of a period keeps the 64^3 run affordable in CI.
TEST(SmoothWave, SecondOrderDiagonal3D) { check_order(3, 16, "van_leer", 1.8, 0.1); }

}  // namespace
}  // namespace cosim::fluid::test
