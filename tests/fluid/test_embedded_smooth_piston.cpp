// Order of accuracy of the embedded boundary on a smooth flow: a wall that recedes from gas at rest with a
// smoothly growing speed drives a simple expansion wave, known exactly along the characteristics, with no
// shock anywhere (the shock pistons of test_embedded_flow.cpp are first order by nature, whatever the
// boundary). The wall comes through the coupled path (coupled::CoupledBoundary: faces of a moving body and the
// interface velocity per face, as from the coupler), along the grid and at 30 degrees to it.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

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
// gas), faces at time t_new with the velocity that brings them there from t_new - dt. In 3D the rectangle
// extruded 1.5 on either side of z_centre (far beyond the thin domain): four side quads and two caps. The
// faces' centres lie inside the domain: a face is sampled (wetted, given a wall pressure) at its centre.
coupling::Faces body_faces(int dim, double deg, double t_new, double dt, double z_centre = 0.0) {
  const double th = deg * std::numbers::pi / 180.0;
  const double n[2] = {-std::sin(th), std::cos(th)}, tg[2] = {std::cos(th), std::sin(th)};
  const double X = wall_x(t_new), v = (wall_x(t_new) - wall_x(t_new - dt)) / dt;
  const double P[2] = {0.5 + X * n[0], kWallY0 + X * n[1]};
  const double L = 1.5, H = 1.5;
  const double A[2] = {P[0] - L * tg[0], P[1] - L * tg[1]}, B[2] = {P[0] + L * tg[0], P[1] + L * tg[1]};
  const double D[2] = {A[0] - H * n[0], A[1] - H * n[1]}, C[2] = {B[0] - H * n[0], B[1] - H * n[1]};
  const double* corner[4] = {A, B, C, D};
  // sides: wall (top), left, bottom, right as (first, second corner, outward normal)
  const int side[4][2] = {{1, 0}, {0, 3}, {3, 2}, {2, 1}};
  const double side_normal[4][2] = {{n[0], n[1]}, {-tg[0], -tg[1]}, {-n[0], -n[1]}, {tg[0], tg[1]}};
  coupling::Faces f;
  f.dim = dim;
  f.nodes_per_face = dim == 2 ? 2 : 4;
  // Shared vertices: corners A, B, C, D (2D), or at z0 then at z1 (3D).
  const double z0 = z_centre - 1.5, z1 = z_centre + 1.5;
  std::vector<std::array<double, 3>> vertex;
  for (const double z : dim == 2 ? std::vector<double>{0.0} : std::vector<double>{z0, z1})
    for (const double* q : corner) vertex.push_back({q[0], q[1], z});
  for (const auto& q : vertex)
    for (int d = 0; d < dim; ++d) f.vertex_position.push_back(q[static_cast<std::size_t>(d)]);
  auto add_face = [&](const std::vector<int>& ids, const std::array<double, 3>& normal) {
    std::array<double, 3> c{0, 0, 0};
    for (const int id : ids) {
      f.face_vertex.push_back(id);
      for (std::size_t d = 0; d < 3; ++d)
        c[d] += vertex[static_cast<std::size_t>(id)][d] / static_cast<double>(ids.size());
    }
    const auto& p0 = vertex[static_cast<std::size_t>(ids[0])];
    const auto& p1 = vertex[static_cast<std::size_t>(ids[1])];
    double area = 0;
    if (dim == 2) {
      area = std::hypot(p1[0] - p0[0], p1[1] - p0[1]);
    } else {  // planar quad: |diagonal x diagonal| / 2
      const auto& p2 = vertex[static_cast<std::size_t>(ids[2])];
      const auto& p3 = vertex[static_cast<std::size_t>(ids[3])];
      const double a[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
      const double b[3] = {p3[0] - p1[0], p3[1] - p1[1], p3[2] - p1[2]};
      area = 0.5 * std::sqrt(std::pow(a[1] * b[2] - a[2] * b[1], 2) + std::pow(a[2] * b[0] - a[0] * b[2], 2) +
                             std::pow(a[0] * b[1] - a[1] * b[0], 2));
    }
    for (int d = 0; d < dim; ++d) {
      f.centre.push_back(c[static_cast<std::size_t>(d)]);
      f.normal.push_back(normal[static_cast<std::size_t>(d)]);
      f.velocity.push_back(d < 2 ? v * n[d] : 0.0);
    }
    f.area.push_back(area);
    ++f.count;
  };
  for (int k = 0; k < 4; ++k) {
    const int p = side[k][0], q = side[k][1];
    const std::array<double, 3> normal{side_normal[k][0], side_normal[k][1], 0.0};
    if (dim == 2) add_face({p, q}, normal);
    else add_face({p, q, q + 4, p + 4}, normal);
  }
  if (dim == 3) {
    add_face({0, 3, 2, 1}, {0, 0, -1});
    add_face({4, 5, 6, 7}, {0, 0, 1});
  }
  f.normal_stress.assign(static_cast<std::size_t>(f.count), 0.0);
  f.impedance.assign(static_cast<std::size_t>(f.count), INFINITY);
  return f;
}

// L1 error of the pressure in the disturbed gas (normal distance from the initial wall below the wave head),
// within 0.15 along the wall of its middle: the corners where the wall meets the domain edges send
// disturbances that cannot reach there by t = 0.2. dim 3: the same flow on a grid 4 cells deep in z (and 4
// cells wide in x when the wall lies along the grid: the flow is one-dimensional there).
double smooth_piston_error(int N, int order, double deg, const char* ghost_pressure, double t_end = kEnd, int dim = 2) {
  const int nx = dim == 3 && deg == 0.0 ? 4 : N, ny = N, nz = dim == 3 ? 4 : 1;
  const double h = 1.0 / N;
  char scene[1024];
  if (dim == 2)
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
  else
    std::snprintf(scene, sizeof(scene), R"(
coupling: {time: {end: 0.2}}
fluid:
  mesh: {cells: [%d, %d, %d], lower: [%.17g, 0.0, 0.0], upper: [%.17g, 1.0, %.17g]}
  phases: [{name: gas, eos: {type: ideal_gas, gamma: 1.4}}]
  time: {end: %g, cfl: 0.5}
  boundaries: {x_lower: transmissive, x_upper: transmissive, y_lower: transmissive, y_upper: transmissive,
               z_lower: transmissive, z_upper: transmissive}
  embedded: {order: %d, ghost_pressure: %s}
  initial:
    state: {rho: 1.0, velocity: [0.0, 0.0, 0.0], p: 1.0}
)",
                  nx, ny, nz, 0.5 - 0.5 * nx * h, 0.5 + 0.5 * nx * h, nz * h, t_end, order, ghost_pressure);
  FluidScene s = parse_fluid_scene(scene);
  auto sim = make_simulation(s);
  auto boundary = coupled::make_coupled_boundary(*sim);
  const double th = deg * std::numbers::pi / 180.0, n[2] = {-std::sin(th), std::cos(th)};
  double t = 0;
  while (t < t_end - 1e-14) {
    const double dt = std::min(sim->stable_dt(), t_end - t);
    const coupling::Faces f = body_faces(dim, deg, t + dt, dt, 0.5 * nz * h);
    const coupling::FluidSamples samples = boundary->receive_faces(f, dt);
    coupling::InterfaceStates
        st;  // of a rigid wall (coupler/interface_conditions.h): its velocity, the fluid's pressure
    st.count = f.count;
    st.phases = 1;
    st.pressure = samples.pressure;
    for (int i = 0; i < f.count; ++i) {
      double un = 0;
      for (int d = 0; d < dim; ++d) un += f.velocity[dim * i + d] * f.normal[dim * i + d];
      st.normal_velocity.push_back(un);
    }
    boundary->apply_states(st);
    sim->advance(dt);
    t += dt;
  }
  const PhaseFields pf = sim->phase_fields(0);
  const std::vector<double> kind = sim->embedded_categories();
  const double c0 = std::sqrt(kGamma * kP0 / kRho0);
  double err = 0;
  int cells = 0;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const std::size_t c = (static_cast<std::size_t>(k) * ny + j) * nx + i;
        if (kind[c] > 1) continue;                                               // flow cells only
        const double x = (i + 0.5 - 0.5 * nx) * h, y = (j + 0.5) * h - kWallY0;  // from the wall's pivot (0.5, kWallY0)
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
void check_accelerating_wall(int dim) {
  constexpr double kMid = 0.05;
  for (double deg : {0.0, 30.0}) {
    const int Ns[3] = {40, 80, 160};
    double e[2][3];
    for (int order = 1; order <= 2; ++order) {
      for (int r = 0; r < 3; ++r) e[order - 1][r] = smooth_piston_error(Ns[r], order, deg, "interface", kMid, dim);
      std::printf(
          "[ measured ] %dD accelerating receding piston at %2.0f deg, t = %g, boundary order %d: L1(p) %.3e %.3e "
          "%.3e (N = 40, 80, 160), observed orders %.2f %.2f\n",
          dim, deg, kMid, order, e[order - 1][0], e[order - 1][1], e[order - 1][2],
          observed_order(e[order - 1][0], e[order - 1][1]), observed_order(e[order - 1][1], e[order - 1][2]));
    }
    EXPECT_GT(observed_order(e[1][0], e[1][2], 4.0), 1.5) << dim << "D " << deg;
    if (deg == 0.0) {
      EXPECT_LT(observed_order(e[0][1], e[0][2]), 0.5) << dim << "D";  // the first-order faces stall
      EXPECT_LT(e[1][1], e[0][1]) << dim << "D";
      EXPECT_LT(e[1][2], e[0][2] / 2.5) << dim << "D";
    } else {
      for (int r = 0; r < 3; ++r) EXPECT_LT(e[1][r], 1.15 * e[0][r]) << dim << "D " << Ns[r];
    }
  }
}

TEST(EmbeddedSmoothPiston, AcceleratingWallFirstAndSecondOrderBoundary) { check_accelerating_wall(2); }

// The same accelerating wall in 3D, its faces as quads through the coupled path: along the grid on a 4 x N x 4
// grid, at 30 degrees on N x N x 4. The 2D findings hold: along the grid the first-order faces stall and
// eq. 23 converges at about second order; at 30 degrees both do. (The body reaches through the domain's
// boundaries in x and z: its image points there read the edge and corner ghost layers, which the boundary
// conditions now fill; they held zeros before and the 3D wall pressure broke down.)
TEST(EmbeddedSmoothPiston, AcceleratingWall3D) { check_accelerating_wall(3); }

}  // namespace
}  // namespace cosim::fluid::test
