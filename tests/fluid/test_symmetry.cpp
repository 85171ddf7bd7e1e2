// Dimension and orientation independence: a 1D problem run along x, y and z in 2D and 3D.
#include <gtest/gtest.h>

#include "fluid_test_utils.h"

namespace cosim::fluid::test {
namespace {

// Sod along axis `axis` of a dim-dimensional box with `n` cells along it and 3 cells across.
std::string sod_along(int dim, int axis, int n) {
  const char* ax[] = {"x", "y", "z"};
  std::string cells = "[", lo = "[", hi = "[", pt = "[", nrm = "[", vel = "[", bnd;
  for (int d = 0; d < dim; ++d) {
    const bool along = d == axis;
    const char* sep = d + 1 < dim ? ", " : "]";
    cells += std::to_string(along ? n : 3) + sep;
    lo += std::string("0.0") + sep;
    hi += std::string(along ? "1.0" : std::to_string(3.0 / n)) + sep;
    pt += std::string(along ? "0.5" : "0.0") + sep;
    nrm += std::string(along ? "1.0" : "0.0") + sep;
    vel += std::string("0.0") + sep;
    if (!along) bnd += std::string("    ") + ax[d] + "_lower: periodic\n    " + ax[d] + "_upper: periodic\n";
    else bnd += std::string("    ") + ax[d] + "_lower: wall\n    " + ax[d] + "_upper: transmissive\n";
  }
  return "fluid:\n  mesh: {cells: " + cells + ", lower: " + lo + ", upper: " + hi +
         "}\n  phases: [{name: gas, eos: {type: ideal_gas, gamma: 1.4}}]\n  time: {end: 0.2}\n  boundaries:\n" + bnd +
         "  initial:\n    state: {rho: 1.0, velocity: " + vel +
         ", p: 1.0}\n    regions:\n      - half_space: {point: " + pt + ", normal: " + nrm +
         "}\n        state: {rho: 0.125, velocity: " + vel + ", p: 0.1}\n";
}

// Density and normal velocity along the axis (the first row of cells across).
void profile(const FluidSimulation& sim, int dim, int axis, int n, std::vector<double>& rho, std::vector<double>& u) {
  PhaseFields f = sim.phase_fields(0);
  rho.resize(n);
  u.resize(n);
  for (int i = 0; i < n; ++i) {
    std::size_t c = axis == 0 ? i : axis == 1 ? static_cast<std::size_t>(i) * 3 : static_cast<std::size_t>(i) * 9;
    if (dim == 1) c = i;
    rho[i] = f.rho[c];
    u[i] = f.velocity[3 * c + axis];
  }
}

TEST(DimensionSymmetry, SameProfileAlongEveryAxis) {
  const int n = 100;
  std::vector<double> r1, u1;
  auto s1 = run_scene(sod_along(1, 0, n));
  profile(*s1, 1, 0, n, r1, u1);
  for (int dim = 2; dim <= 3; ++dim) {
    std::vector<double> rx, ux;
    auto sx = run_scene(sod_along(dim, 0, n));
    profile(*sx, dim, 0, n, rx, ux);
    // Same grid spacing in every direction: x, y and z runs are identical to round-off.
    for (int axis = 1; axis < dim; ++axis) {
      std::vector<double> r, u;
      auto s = run_scene(sod_along(dim, axis, n));
      profile(*s, dim, axis, n, r, u);
      for (int i = 0; i < n; ++i) {
        EXPECT_NEAR(r[i], rx[i], 1e-13) << dim << "D axis " << axis << " cell " << i;
        EXPECT_NEAR(u[i], ux[i], 1e-13) << dim << "D axis " << axis << " cell " << i;
      }
    }
    // Multi-D runs take smaller steps (the CFL sums over axes); the profile matches 1D closely.
    const double dr = l1_error(rx, r1), du = l1_error(ux, u1);
    std::printf("%dD vs 1D Sod: L1 difference rho %.2e, u %.2e\n", dim, dr, du);
    EXPECT_LT(dr, 2e-3);
    EXPECT_LT(du, 4e-3);
    // The transverse velocity stays exactly zero.
    PhaseFields f = sx->phase_fields(0);
    for (std::size_t c = 0; c < f.rho.size(); ++c) EXPECT_EQ(f.velocity[3 * c + 1], 0.0);
  }
}

}  // namespace
}  // namespace cosim::fluid::test

namespace cosim::fluid::test {
namespace {

// OpenMP decomposition does not change the answer: 1 and 2 threads give bit-identical fields
// (rows and layer chunks are computed independently, each face once per chunk).
TEST(Threads, OneAndTwoThreadsGiveIdenticalResults) {
  const std::string scene = R"(
fluid:
  mesh: {cells: [40, 36], lower: [0.0, 0.0], upper: [1.0, 0.9]}
  phases:
    - {name: gas, material: air}
    - {name: dust, material: tungsten}
  time: {end: 2.0e-4}
  initial:
    state: {p: 1.0e5, T: 300, velocity: [0.0, 0.0], alpha: [0.99, 0.01]}
    regions:
      - sphere: {center: [0.4, 0.5], radius: 0.2}
        state: {p: 5.0e6, T: 900, velocity: [30.0, -10.0], alpha: [0.9, 0.1]}
)";
  auto a = run_scene(scene, {"fluid.threads=1"});
  auto b = run_scene(scene, {"fluid.threads=2"});
  for (int k = 0; k < 2; ++k) {
    PhaseFields fa = a->phase_fields(k), fb = b->phase_fields(k);
    EXPECT_EQ(fa.rho, fb.rho) << k;
    EXPECT_EQ(fa.p, fb.p) << k;
    EXPECT_EQ(fa.velocity, fb.velocity) << k;
    EXPECT_EQ(fa.alpha, fb.alpha) << k;
  }
}

}  // namespace
}  // namespace cosim::fluid::test
