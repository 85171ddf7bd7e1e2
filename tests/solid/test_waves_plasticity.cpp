// Elastic plate (uniaxial strain) wave speed, and the Hugoniot elastic limit of steel under uniaxial strain.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>

#include "common/eos/materials.h"
#include "solid_solver/materials/strength.h"
#include "solid_test_util.h"

using namespace cosim::solid;
using solid_test::run_to;

namespace {
// Position of the velocity front (first crossing of v0/2 from the undisturbed side), along y = 0.
double front_position(const Simulation& sim, double v0) {
  const Mesh& m = sim.mesh();
  const State& st = sim.state();
  std::vector<std::pair<double, double>> xv;
  for (int n = 0; n < m.num_nodes; ++n)
    if (std::abs(m.x0[n * 2 + 1]) < 1e-12) xv.push_back({st.x[n * 2], st.v[n * 2]});
  std::sort(xv.begin(), xv.end());
  for (std::size_t i = xv.size() - 1; i > 0; --i)
    if (xv[i - 1].second >= 0.5 * v0 && xv[i].second < 0.5 * v0) {
      const double f = (xv[i - 1].second - 0.5 * v0) / (xv[i - 1].second - xv[i].second);
      return xv[i - 1].first + f * (xv[i].first - xv[i - 1].first);
    }
  return 0.0;
}
}  // namespace

// A velocity step v0 on the end of a laterally confined plate travels at c_L = sqrt((K + 4G/3) / rho).
TEST(SolidWaves, ElasticPlateLongitudinalSpeed) {
  const double K = 1.6e11, G = 8.0e10, rho = 7800.0, v0 = 1.0;
  SolidScene s = parse_solid_scene(fmt::format(R"(
solid:
  mesh: {{cells: [400, 1], lower: [0, 0], upper: [1.0, 0.0025]}}
  blocks:
    - name: plate
      eos: {{type: linear_elastic, bulk_modulus: {}}}
      density: {}
      strength: {{shear_modulus: {}}}
  boundaries:
    - {{set: x_lower, type: velocity, vx: {}}}
    - {{set: y_lower, type: symmetry}}
    - {{set: y_upper, type: symmetry}}
  time: {{end: 1.0}}
)",
                                               K, rho, G, v0));
  Simulation sim(s);
  const double cL = std::sqrt((K + 4.0 * G / 3.0) / rho);
  double xf[2];
  const double targets[2] = {0.25 / cL, 0.75 / cL};
  for (int k = 0; k < 2; ++k) {
    run_to(sim, targets[k]);
    xf[k] = front_position(sim, v0);
  }
  // Velocities are at t^{n-1/2}; both samples use the same convention, so the half step cancels in the speed.
  const double c_num = (xf[1] - xf[0]) / (targets[1] - targets[0]);
  const double err = (c_num - cL) / cL;
  std::printf("[ measured ] c_L numerical %.2f m/s, theory %.2f m/s, error %.3f%%\n", c_num, cL, 100 * err);
  EXPECT_LT(std::abs(err), 0.01);
}

namespace {
struct HelResult {
  double sxx_at_yield = 0, hel = 0, max_overshoot = 0, final_diff = 0, Y = 0;
};

HelResult uniaxial_strain(const std::string& eos_yaml, double G, double Y, double K) {
  SolidScene s = solid_test::uniaxial_strain_scene(eos_yaml, G, Y);
  Simulation sim(s);
  const State& st = sim.state();
  HelResult r;
  r.Y = Y;
  const double nu = (3 * K - 2 * G) / (2 * (3 * K + G));
  r.hel = (1 - nu) / (1 - 2 * nu) * Y;
  double prev_sxx = 0;
  bool yielded = false;
  const double dt = 0.5 * sim.stable_dt();
  // Strain rate 100 /s; yield near strain Y/(2G) ~ 3e-3 to 6e-3: ~700-1300 steps to yield.
  for (int k = 0; k < 5000; ++k) {
    sim.advance(dt);
    const double sxx = -(st.p[0] + st.q[0]) + st.s[0];
    r.max_overshoot = std::max(r.max_overshoot, von_mises(&st.s[0]) / Y - 1.0);
    if (!yielded && st.eps_p[0] > 0) {
      yielded = true;
      r.sxx_at_yield = prev_sxx;
    }
    prev_sxx = sxx;
  }
  r.final_diff = st.s[0] - st.s[1];  // sigma_xx - sigma_yy
  EXPECT_TRUE(yielded);
  return r;
}
}  // namespace

// Uniaxial strain: yield at sigma_xx = HEL = (1-nu)/(1-2nu) Y, then sigma_xx - sigma_yy stays at -Y (compression).
TEST(SolidPlasticity, UniaxialStrainLinearBulkReachesHel) {
  const double K = 1.6e11, G = 8.0e10, Y = 1.0e9;
  auto r =
      uniaxial_strain(fmt::format("eos: {{type: linear_elastic, bulk_modulus: {}}}\n      density: 7800", K), G, Y, K);
  std::printf("[ measured ] linear bulk: |sigma_xx| at yield %.5g Pa, HEL %.5g Pa (%.3f%%)\n", -r.sxx_at_yield, r.hel,
              100 * (-r.sxx_at_yield - r.hel) / r.hel);
  EXPECT_NEAR(-r.sxx_at_yield / r.hel, 1.0, 0.005);
  EXPECT_LT(r.max_overshoot, 1e-12);
  EXPECT_NEAR(r.final_diff / Y, -1.0, 1e-9);
}

TEST(SolidPlasticity, UniaxialStrainSteelMieGruneisenReachesHel) {
  const auto* steel = cosim::eos::find_material("steel");
  ASSERT_TRUE(steel && steel->mg);
  const double K = steel->mg->rho0 * steel->mg->c0 * steel->mg->c0, G = 7.9e10, Y = 0.5e9;
  auto r = uniaxial_strain("material: steel", G, Y, K);
  std::printf("[ measured ] steel (Mie-Grueneisen): |sigma_xx| at yield %.5g Pa, HEL %.5g Pa (%.3f%%)\n",
              -r.sxx_at_yield, r.hel, 100 * (-r.sxx_at_yield - r.hel) / r.hel);
  EXPECT_NEAR(-r.sxx_at_yield / r.hel, 1.0, 0.01);
  EXPECT_LT(r.max_overshoot, 1e-12);
  EXPECT_NEAR(r.final_diff / Y, -1.0, 1e-9);
}
