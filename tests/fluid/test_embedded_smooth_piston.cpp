// Order of accuracy of the embedded boundary on a smooth flow: a wall that recedes from gas at rest with a
// smoothly growing speed drives a simple expansion wave, known exactly along the characteristics, with no
// shock anywhere (the shock pistons of test_embedded_flow.cpp are first order by nature, whatever the
// boundary). The wall comes through the coupled path (coupled::CoupledBoundary: faces of a moving body and the
// interface velocity per face, as from the coupler), along the grid and at 30 degrees to it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "fluid_solver/core/scene.h"
#include "fluid_solver/coupled/coupled_boundary.h"
#include "fluid_test_utils.h"

namespace cosim::fluid::test {
namespace {

constexpr double kGamma = 1.4, kRho0 = 1.0, kP0 = 1.0;
constexpr double kV0 = 0.3;      // final speed of the receding wall
constexpr double kRamp = 0.1;    // the speed grows as (1 - cos(pi t / T)) / 2 over T
constexpr double kEnd = 0.2;     // the wall moves at constant speed over the second half
constexpr double kWallY0 = 0.3;  // the wall passes through (0.5, kWallY0) at t = 0

// Displacement along the wall normal (into the gas positive) and speed of the wall.
double wall_x(double t) {
  if (t <= kRamp) return -0.5 * kV0 * (t - kRamp / std::numbers::pi * std::sin(std::numbers::pi * t / kRamp));
  return -0.5 * kV0 * kRamp - kV0 * (t - kRamp);
}
double wall_v(double t) { return t <= kRamp ? -0.5 * kV0 * (1 - std::cos(std::numbers::pi * t / kRamp)) : -kV0; }

// Simple wave of a piston with path X(t) (Courant-Friedrichs; Toro section 3.1.3 for the invariants): the C+
// characteristic that leaves the wall at time tau carries u = V(tau) and c = c0 + (gamma - 1)/2 V(tau), along
// x = X(tau) + (u + c)(t - tau). The expansion fans them out, so tau(x, t) is unique.
double exact_pressure(double xn, double t) {
  const double c0 = std::sqrt(kGamma * kP0 / kRho0);
  if (xn >= c0 * t) return kP0;
  const auto c_of = [&](double tau) { return c0 + 0.5 * (kGamma - 1) * wall_v(tau); };
  double lo = 0, hi = t;  // f(lo) > 0 > f(hi)
  for (int it = 0; it < 100; ++it) {
    const double tau = 0.5 * (lo + hi);
    const double f = wall_x(tau) + (wall_v(tau) + c_of(tau)) * (t - tau) - xn;
    (f > 0 ? lo : hi) = tau;
  }
  const double c = c_of(0.5 * (lo + hi));
  return kP0 * std::pow(c / c0, 2 * kGamma / (kGamma - 1));
}

// The moving body as a solid would send it: a 3 x 1.5 rectangle whose top face is the wall (normal n into the
// gas), faces at time t_new with the velocity that brings them there from t_new - dt.
coupling::Faces body_faces(double deg, double t_new, double dt) {
  const double th = deg * std::numbers::pi / 180.0;
  const double n[2] = {-std::sin(th), std::cos(th)}, tg[2] = {std::cos(th), std::sin(th)};
  const double X = wall_x(t_new), v = (wall_x(t_new) - wall_x(t_new - dt)) / dt;
  const double P[2] = {0.5 + X * n[0], kWallY0 + X * n[1]};
  const double L = 1.5, H = 1.5;
  const double A[2] = {P[0] - L * tg[0], P[1] - L * tg[1]}, B[2] = {P[0] + L * tg[0], P[1] + L * tg[1]};
  const double D[2] = {A[0] - H * n[0], A[1] - H * n[1]}, C[2] = {B[0] - H * n[0], B[1] - H * n[1]};
  coupling::Faces f;
  f.dim = 2;
  f.count = 4;
  f.nodes_per_face = 2;
  f.vertex_position = {A[0], A[1], B[0], B[1], C[0], C[1], D[0], D[1]};
  f.face_vertex = {1, 0, 0, 3, 3, 2, 2, 1};  // wall (top), left, bottom, right
  f.normal = {n[0], n[1], -tg[0], -tg[1], -n[0], -n[1], tg[0], tg[1]};
  const double* ends[4][2] = {{B, A}, {A, D}, {D, C}, {C, B}};
  for (auto& e : ends) {
    f.centre.push_back(0.5 * (e[0][0] + e[1][0]));
    f.centre.push_back(0.5 * (e[0][1] + e[1][1]));
    f.area.push_back(std::hypot(e[1][0] - e[0][0], e[1][1] - e[0][1]));
    f.velocity.push_back(v * n[0]);
    f.velocity.push_back(v * n[1]);
  }
  f.normal_stress.assign(4, 0.0);
  f.impedance.assign(4, INFINITY);
  return f;
}

// L1 error of the pressure in the disturbed gas (normal distance from the initial wall below the wave head),
// within 0.15 along the wall of its middle: the corners where the wall meets the domain edges send
// disturbances that cannot reach there by t = 0.2.
double smooth_piston_error(int N, int order, double deg, const char* ghost_pressure, double t_end = kEnd) {
  char scene[1024];
  std::snprintf(scene, sizeof(scene), R"(
coupling: {time: {end: 0.2}}
fluid:
  mesh: {cells: [%d, %d], lower: [0.0, 0.0], upper: [1.0, 1.0]}
  phases: [{name: gas, eos: {type: ideal_gas, gamma: 1.4}}]
  time: {end: %g, cfl: 0.5}
  boundaries: {x_lower: transmissive, x_upper: transmissive, y_lower: transmissive, y_upper: transmissive}
  embedded: {order: %d, ghost_pressure: %s}
  initial:
    state: {rho: 1.0, velocity: [0.0, 0.0], p: 1.0}
)",
                N, N, t_end, order, ghost_pressure);
  FluidScene s = parse_fluid_scene(scene);
  auto sim = make_simulation(s);
  auto boundary = coupled::make_coupled_boundary(*sim);
  const double th = deg * std::numbers::pi / 180.0, n[2] = {-std::sin(th), std::cos(th)};
  double t = 0;
  while (t < t_end - 1e-14) {
    const double dt = std::min(sim->stable_dt(), t_end - t);
    const coupling::Faces f = body_faces(deg, t + dt, dt);
    const coupling::FluidSamples samples = boundary->receive_faces(f, dt);
    coupling::InterfaceStates
        st;  // of a rigid wall (coupler/interface_conditions.h): its velocity, the fluid's pressure
    st.count = f.count;
    st.phases = 1;
    st.pressure = samples.pressure;
    for (int i = 0; i < f.count; ++i)
      st.normal_velocity.push_back(f.velocity[2 * i] * f.normal[2 * i] + f.velocity[2 * i + 1] * f.normal[2 * i + 1]);
    boundary->apply_states(st);
    sim->advance(dt);
    t += dt;
  }
  const PhaseFields pf = sim->phase_fields(0);
  const std::vector<double> kind = sim->embedded_categories();
  const double c0 = std::sqrt(kGamma * kP0 / kRho0);
  double err = 0;
  int cells = 0;
  for (int j = 0; j < N; ++j)
    for (int i = 0; i < N; ++i) {
      const std::size_t c = static_cast<std::size_t>(j) * N + i;
      if (kind[c] > 1) continue;  // flow cells only
      const double x = (i + 0.5) / N - 0.5, y = (j + 0.5) / N - kWallY0;
      const double xn = x * n[0] + y * n[1], along = x * n[1] - y * n[0];
      if (std::abs(along) > 0.15 || xn > c0 * t_end) continue;
      err += std::abs(pf.p[c] - exact_pressure(xn, t_end));
      ++cells;
    }
  EXPECT_GT(cells, 10);
  return err / cells;
}

// Three treatments at N = 40, 80, 160: first-order boundary, second-order face states (eq. 23), both with the
// ghost pressure extrapolated from the wall pressure, and the second-order face states with the ghost pressure
// copied from the image point (the even reflection, blind to the wall's acceleration).
TEST(EmbeddedSmoothPiston, ConvergenceWithFirstAndSecondOrderBoundary) {
  for (double deg : {0.0, 30.0}) {
    const int Ns[3] = {40, 80, 160};
    const struct {
      int order;
      const char* ghost_pressure;
    } cases[3] = {{1, "interface"}, {2, "interface"}, {2, "image"}};
    double e[3][3];
    for (int c = 0; c < 3; ++c) {
      for (int r = 0; r < 3; ++r) e[c][r] = smooth_piston_error(Ns[r], cases[c].order, deg, cases[c].ghost_pressure);
      std::printf(
          "[ measured ] receding smooth piston at %2.0f deg, boundary order %d, ghost pressure %-9s: L1(p) "
          "%.3e %.3e %.3e (N = 40, 80, 160), observed orders %.2f %.2f\n",
          deg, cases[c].order, cases[c].ghost_pressure, e[c][0], e[c][1], e[c][2], observed_order(e[c][0], e[c][1]),
          observed_order(e[c][1], e[c][2]));
    }
    // The wall's acceleration needs the extrapolated ghost pressure: the copied one is 2-3x less accurate at
    // 160 cells.
    EXPECT_LT(e[1][2], 0.5 * e[2][2]) << deg;
    // With it: more than first order over 40 -> 160 on both walls; the second-order face states are
    // better than the first-order ones along the grid (by 1.5-2.2x) and within 20% of them at 30 degrees (measured up
    // to 1.18x: there the first-order errors cancel along the staircase, AcceleratingWallFirstAndSecondOrderBoundary).
    EXPECT_GT(observed_order(e[1][0], e[1][2], 4.0), 1.3) << deg;
    for (int r = 0; r < 3; ++r) {
      if (deg == 0.0) EXPECT_LT(e[1][r], e[0][r] / 1.4) << Ns[r];
      else EXPECT_LT(e[1][r], 1.2 * e[0][r]) << Ns[r];
    }
  }
}

// The same wall stopped at t = 0.05, in the middle of its acceleration, so that the whole disturbed gas
// still feels the boundary treatment of the last few steps (at t = 0.2 the gas next to the wall is a
// uniform state that both treatments get to 1e-6). Along the grid every wall face sits at the same
// distance d from its cell centre, so the first-order face states (u* = u_I at the grid face instead of
// at the wall) make an error of the same sign all along the wall and stall (observed order 0.2 over
// 80 -> 160); the d-weighted face states converge at second order. At 30 degrees d runs through [0, 1)
// along the staircase, the first-order errors cancel between neighbouring faces, and both treatments
// converge at about second order with errors within 10%.
TEST(EmbeddedSmoothPiston, AcceleratingWallFirstAndSecondOrderBoundary) {
  constexpr double kMid = 0.05;
  for (double deg : {0.0, 30.0}) {
    const int Ns[3] = {40, 80, 160};
    double e[2][3];
    for (int order = 1; order <= 2; ++order) {
      for (int r = 0; r < 3; ++r) e[order - 1][r] = smooth_piston_error(Ns[r], order, deg, "interface", kMid);
      std::printf(
          "[ measured ] accelerating receding piston at %2.0f deg, t = %g, boundary order %d: L1(p) %.3e %.3e "
          "%.3e (N = 40, 80, 160), observed orders %.2f %.2f\n",
          deg, kMid, order, e[order - 1][0], e[order - 1][1], e[order - 1][2],
          observed_order(e[order - 1][0], e[order - 1][1]), observed_order(e[order - 1][1], e[order - 1][2]));
    }
    EXPECT_GT(observed_order(e[1][0], e[1][2], 4.0), 1.5) << deg;
    if (deg == 0.0) {
      EXPECT_LT(e[1][1], e[0][1]) << deg;
      EXPECT_LT(e[1][2], e[0][2] / 2.5) << deg;
    } else {
      for (int r = 0; r < 3; ++r) EXPECT_LT(e[1][r], 1.15 * e[0][r]) << Ns[r];
    }
  }
}

}  // namespace
}  // namespace cosim::fluid::test
