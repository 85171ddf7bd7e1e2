// Patch test: a uniform strain rate imposed on the boundary of a distorted mesh is reproduced exactly inside
// (interior nodes keep the linear velocity field, every element has the same stress and density).
// Rigid rotation: a pre-stressed block turned by 90 degrees keeps its stress invariants and its stress rotates
// with the body (Jaumann rate with the Hughes-Winget increment: exact for rigid rotations).
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>

#include "solid_test_util.h"

using namespace cosim::solid;
using cosim::solid::solid_test::distort_interior;

namespace {

SolidScene elastic_scene(int dim, int n) {
  std::string cells = dim == 2 ? fmt::format("[{0}, {0}]", n) : fmt::format("[{0}, {0}, {0}]", n);
  std::string lo = dim == 2 ? "[-1, -1]" : "[-1, -1, -1]", hi = dim == 2 ? "[1, 1]" : "[1, 1, 1]";
  return parse_solid_scene(fmt::format(R"(
solid:
  mesh: {{cells: {}, lower: {}, upper: {}}}
  blocks:
    - name: metal
      eos: {{type: linear_elastic, bulk_modulus: 1.6e11}}
      density: 7800
      strength: {{shear_modulus: 8.0e10, yield_stress: 1.0e12}}
  numerics: {{q_quadratic: 0, q_linear: 0, hourglass: 0.1}}
  time: {{end: 1.0}}
)",
                                       cells, lo, hi));
}

void patch_test(int dim) {
  SolidScene s = elastic_scene(dim, 4);
  Mesh m = build_mesh(s);
  distort_interior(m, s.lower, s.upper, 0.5, 0.25);
  Simulation sim(s, m);
  State& st = sim.state();
  // Velocity gradient A (expansion + shear), v = A x0 on every node; boundary nodes prescribed.
  const double A[3][3] = {{10.0, 3.0, -2.0}, {-1.0, 5.0, 4.0}, {2.0, -3.0, 8.0}};  // [1/s]
  const int D = dim;
  std::vector<double> vexact(st.v.size());
  for (int n = 0; n < m.num_nodes; ++n) {
    bool boundary = false;
    for (int d = 0; d < D; ++d) {
      const double x = m.x0[n * D + d];
      boundary = boundary || std::abs(std::abs(x) - 1.0) < 1e-12;
    }
    for (int i = 0; i < D; ++i) {
      double v = 0;
      for (int j = 0; j < D; ++j) v += A[i][j] * m.x0[n * D + j];
      vexact[n * D + i] = v;
      st.v[n * D + i] = v;
      if (boundary) {
        st.bc_mask[n] |= static_cast<std::uint8_t>(1u << i);
        st.bc_value[n * D + i] = v;
      }
    }
  }
  sim.element_update(0.0);
  const double dt = 0.5 * sim.stable_dt();
  for (int k = 0; k < 50; ++k) sim.advance(dt);
  double vmax = 0, verr = 0;
  for (std::size_t i = 0; i < st.v.size(); ++i) {
    vmax = std::max(vmax, std::abs(vexact[i]));
    verr = std::max(verr, std::abs(st.v[i] - vexact[i]));
  }
  EXPECT_LT(verr / vmax, 1e-10) << "interior nodes left the linear velocity field";
  const int ne = m.num_elements;
  double smax = 0, serr = 0, rerr = 0;
  const double rho0 = st.emass[0] / st.vol[0];
  for (int z = 0; z < ne; ++z) {
    for (int k = 0; k < 6; ++k) {
      smax = std::max(smax, std::abs(st.s[k]));
      serr = std::max(serr, std::abs(st.s[z * 6 + k] - st.s[k]));
    }
    smax = std::max(smax, std::abs(st.p[0]));
    serr = std::max(serr, std::abs(st.p[z] - st.p[0]));
    rerr = std::max(rerr, std::abs(st.emass[z] / st.vol[z] - rho0) / rho0);
  }
  EXPECT_GT(smax, 1e8);  // the test is not vacuous
  EXPECT_LT(serr / smax, 1e-10) << "stress not uniform";
  EXPECT_LT(rerr, 1e-12) << "density not uniform";
}

// Rotation matrix about unit axis n by angle th (Rodrigues).
void rotation(const double n[3], double th, double R[3][3]) {
  const double c = std::cos(th), s = std::sin(th);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) R[i][j] = (i == j ? c : 0.0) + (1 - c) * n[i] * n[j];
  R[0][1] -= s * n[2];
  R[0][2] += s * n[1];
  R[1][0] += s * n[2];
  R[1][2] -= s * n[0];
  R[2][0] -= s * n[1];
  R[2][1] += s * n[0];
}

void rotation_test(int dim) {
  SolidScene s = elastic_scene(dim, 2);
  // Pre-stress: a traceless deviator with shear.
  s.blocks[0].deviator = dim == 2 ? std::array<double, 6>{3e8, -1e8, -2e8, 1.5e8, 0, 0}
                                  : std::array<double, 6>{3e8, -1e8, -2e8, 1.5e8, -0.7e8, 0.4e8};
  Mesh m = build_mesh(s);
  distort_interior(m, s.lower, s.upper, 1.0, 0.2);
  Simulation sim(s, m);
  State& st = sim.state();
  const int D = dim, nn = m.num_nodes;
  double axis[3] = {0, 0, 1};
  if (dim == 3) {
    const double l = std::sqrt(1.0 + 4.0 + 9.0);
    axis[0] = 1 / l;
    axis[1] = 2 / l;
    axis[2] = 3 / l;
  }
  const int steps = 400;
  const double total = 0.5 * M_PI, dt = 1e-3;
  for (int k = 1; k <= steps; ++k) {
    double R[3][3];
    rotation(axis, total * k / steps, R);
    for (int n = 0; n < nn; ++n) {
      double xn[3] = {0, 0, 0};
      for (int i = 0; i < D; ++i)
        for (int j = 0; j < D; ++j) xn[i] += R[i][j] * m.x0[n * D + j];
      for (int i = 0; i < D; ++i) {
        st.v[n * D + i] = (xn[i] - st.x[n * D + i]) / dt;
        st.vbar[n * D + i] = st.v[n * D + i];
        st.x[n * D + i] = xn[i];
      }
    }
    sim.element_update(dt);
  }
  double R[3][3];
  rotation(axis, total, R);
  const auto& d0 = s.blocks[0].deviator;
  const double S0[3][3] = {{d0[0], d0[3], d0[5]}, {d0[3], d0[1], d0[4]}, {d0[5], d0[4], d0[2]}};
  double S[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      S[i][j] = 0;
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l) S[i][j] += R[i][k] * S0[k][l] * R[j][l];
    }
  const double expect[6] = {S[0][0], S[1][1], S[2][2], S[0][1], S[1][2], S[0][2]};
  auto j2 = [](const double* v) {
    return v[0] * v[0] + v[1] * v[1] + v[2] * v[2] + 2 * (v[3] * v[3] + v[4] * v[4] + v[5] * v[5]);
  };
  auto j3 = [](const double* v) {
    return v[0] * (v[1] * v[2] - v[4] * v[4]) - v[3] * (v[3] * v[2] - v[4] * v[5]) + v[5] * (v[3] * v[4] - v[1] * v[5]);
  };
  const double J2 = j2(d0.data()), J3 = j3(d0.data());
  for (int z = 0; z < m.num_elements; ++z) {
    const double* sz = &st.s[z * 6];
    EXPECT_NEAR(j2(sz) / J2, 1.0, 1e-10) << "element " << z;
    EXPECT_NEAR(j3(sz) / J3, 1.0, 1e-9) << "element " << z;
    for (int k = 0; k < 6; ++k) EXPECT_NEAR(sz[k], expect[k], 1e-7 * std::sqrt(J2)) << "element " << z << " comp " << k;
    EXPECT_NEAR(st.p[z], 0.0, 1e-6 * std::sqrt(J2));
  }
}

}  // namespace

TEST(SolidPatch, UniformStrainOnDistortedQuads) { patch_test(2); }
TEST(SolidPatch, UniformStrainOnDistortedHexes) { patch_test(3); }
TEST(SolidJaumann, RigidRotationKeepsStressInvariants2D) { rotation_test(2); }
TEST(SolidJaumann, RigidRotationKeepsStressInvariants3D) { rotation_test(3); }
