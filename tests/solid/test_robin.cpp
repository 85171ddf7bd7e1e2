// The fluid's Robin condition on the solid (Simulation::set_face_impedances; docs/methods.md §4.4): a face
// loaded by p_w(v) = J + Z v, taken at the velocity the step reaches. Exact reference: a rigid block under it
// obeys M dv/dt = -A (J + Z v), v(t) = v_inf + (v0 - v_inf) exp(-t/tau), v_inf = -J/Z, tau = M/(Z A).
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>

#include "solid_test_util.h"

using namespace cosim::solid;

namespace {

// One coupled cycle as the solid runner does it: the faces are sent (v_sent = the current normal velocity), the
// coupler's pressure J + Z v_sent and impedance Z come back for the faces with outward normal +x (all faces
// when `everywhere`), nothing for the others; then the step.
void robin_cycle(Simulation& sim, double J, double Z, double dt, bool everywhere = false) {
  const BoundaryFaces& f = sim.boundary_faces();
  const int D = sim.mesh().dim;
  std::vector<double> p(f.count, 0.0), z(f.count, 0.0);
  for (int i = 0; i < f.count; ++i) {
    if (!everywhere && f.normal[static_cast<std::size_t>(i) * D] < 0.9) continue;
    double vn = 0;
    for (int d = 0; d < D; ++d)
      vn += f.velocity[static_cast<std::size_t>(i) * D + d] * f.normal[static_cast<std::size_t>(i) * D + d];
    p[i] = J + Z * vn;
    z[i] = Z;
  }
  sim.set_face_pressures(p);
  sim.set_face_impedances(z);
  sim.advance(dt);
}

SolidScene block_scene(const std::string& block) {
  return parse_solid_scene(fmt::format(R"(
solid:
  mesh: {{cells: [4, 2], upper: [2, 1]}}
  blocks:
    - {}
  time: {{end: 1.0}}
)",
                                       block));
}

}  // namespace

// Heavy (r = dt Z A / M = 2e-3: the centred step) and very light (r = 2e3: beyond any explicit limit, where
// the explicit load would grow as (1 - r)^n): both follow the exact relaxation to -J/Z, the light one without
// overshoot or ringing; the boundary work equals the energy change.
TEST(SolidRobin, RigidBlockRelaxesToTheFluidsCharacteristic) {
  const double J = 1e5, Z = 400.0, A = 1.0, dt = 1e-3;
  for (double rho : {100.0, 1e-4}) {
    Simulation sim(block_scene(fmt::format("{{name: b, rigid: true, density: {}}}", rho)));
    const double M = sim.rigid_bodies().at(0).mass, tau = M / (Z * A), v_inf = -J / Z;
    const double e0 = sim.energy().total();
    double worst = 0, prev = 0;
    bool monotone = true;
    for (int n = 0; n < 200; ++n) {
      robin_cycle(sim, J, Z, dt);
      const double v = sim.rigid_bodies()[0].V[0];
      // The leapfrog velocity V^{n+1/2} belongs to t^{n+1/2}... its step ends at t^{n+1}: compare there.
      const double exact = v_inf * (1.0 - std::exp(-sim.time() / tau));
      worst = std::max(worst, std::abs(v - exact) / std::abs(v_inf));
      monotone = monotone && v <= prev + 1e-12 * std::abs(v_inf) && v >= v_inf * (1 + 1e-12);
      prev = v;
    }
    std::printf("[ measured ] rigid block rho %g (r = %.3g): max |v - exact| %.3g of |v_inf|\n", rho, dt * Z * A / M,
                worst);
    EXPECT_TRUE(monotone) << "rho " << rho;
    EXPECT_LT(worst, rho > 1 ? 1e-5 : 2e-3) << "rho " << rho;
    const auto e = sim.energy();
    EXPECT_NEAR(e.total() - e0, e.boundary_work, 1e-9 * std::max(1.0, std::abs(e.boundary_work))) << "rho " << rho;
  }
}

// Deformable: a gas block at the fluid's pressure with J = p - Z * 0 stays at rest to round-off (the Robin part
// adds nothing in equilibrium); a light gas block (rho 1e-3, z_s / Z = 0.03) under J = 2e5 on its +x face and
// held at x = 0 settles smoothly to the traction the fluid's characteristic allows: the +x face's velocity
// tends to (p_block - J)/Z, stable at the solid's own stable step, and the energy balance holds.
TEST(SolidRobin, DeformableBlockKeepsEquilibriumAndTakesTheCharacteristic) {
  {
    Simulation sim(
        block_scene("{name: b, eos: {type: ideal_gas, gamma: 1.4}, density: 1.0, initial: {pressure: "
                    "1.0e5}}"));
    for (int n = 0; n < 50; ++n) robin_cycle(sim, 1e5, 400.0, 0.5 * sim.stable_dt(), true);
    double vmax = 0;
    for (double v : sim.state().v) vmax = std::max(vmax, std::abs(v));
    EXPECT_LT(vmax, 1e-9);
  }
  SolidScene s = parse_solid_scene(R"(
solid:
  mesh: {cells: [8, 1], upper: [1, 0.1]}
  blocks:
    - {name: b, eos: {type: ideal_gas, gamma: 1.4}, density: 1.0e-3, initial: {pressure: 1.5e5}}
  boundaries:
    - {set: x_lower, type: fixed}
    - {set: y_lower, type: symmetry}
    - {set: y_upper, type: symmetry}
  time: {end: 1.0}
)");
  Simulation sim(s);
  const double J = 2e5, Z = 400.0;
  const double e0 = sim.energy().total();
  for (int n = 0; n < 400; ++n) {
    robin_cycle(sim, J, Z, 0.9 * sim.stable_dt());
    for (double v : sim.state().v) ASSERT_TRUE(std::isfinite(v)) << "step " << n;
  }
  // The +x face: its velocity meets the characteristic J + Z v = the block's boundary pressure within 2%.
  const BoundaryFaces& f = sim.boundary_faces();
  for (int i = 0; i < f.count; ++i) {
    if (f.normal[2 * static_cast<std::size_t>(i)] < 0.9) continue;
    const double v = f.velocity[2 * static_cast<std::size_t>(i)], p_s = -f.normal_stress[i];
    std::printf("[ measured ] light gas block: face velocity %.4g m/s, J + Z v = %.5g Pa, block pressure %.5g Pa\n", v,
                J + Z * v, p_s);
    EXPECT_LT(v, 0.0);  // the fluid pushes the lighter-pressure block in
    EXPECT_NEAR(J + Z * v, p_s, 0.02 * p_s);
  }
  const auto e = sim.energy();
  EXPECT_NEAR(e.total() - e0, e.boundary_work, 1e-6 * std::abs(e0));
}
