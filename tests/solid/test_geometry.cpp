// Element geometry: B_a = dV/dx_a exactly (finite differences), sum_a x_a (x) B_a = V I, volume of a
// distorted element equals the exact trilinear volume of its affine image.
#include <gtest/gtest.h>

#include "solid_solver/kinematics/element_geometry.h"
#include "solid_test_util.h"

using namespace cosim::solid;

namespace {
template <int D>
void check_element(double (&x)[ElemTraits<D>::npe][D]) {
  constexpr int N = ElemTraits<D>::npe;
  double B[N][D];
  const double V = element_b_matrix(x, B);
  ASSERT_GT(V, 0.0);
  for (int i = 0; i < D; ++i)
    for (int j = 0; j < D; ++j) {
      double sum = 0;
      for (int a = 0; a < N; ++a) sum += x[a][i] * B[a][j];
      EXPECT_NEAR(sum, i == j ? V : 0.0, 1e-13) << i << j;
    }
  const double eps = 1e-6;
  for (int a = 0; a < N; ++a)
    for (int d = 0; d < D; ++d) {
      double Bt[N][D];
      const double x0 = x[a][d];
      x[a][d] = x0 + eps;
      const double vp = element_b_matrix(x, Bt);
      x[a][d] = x0 - eps;
      const double vm = element_b_matrix(x, Bt);
      x[a][d] = x0;
      EXPECT_NEAR((vp - vm) / (2 * eps), B[a][d], 1e-9) << "node " << a << " dim " << d;
    }
}
}  // namespace

TEST(SolidGeometry, QuadBMatrixIsVolumeDerivative) {
  double x[4][2] = {{0, 0}, {1.2, 0.1}, {1.0, 0.9}, {-0.1, 1.3}};
  check_element<2>(x);
  double B[4][2];
  double sq[4][2] = {{0, 0}, {2, 0}, {2, 3}, {0, 3}};
  EXPECT_DOUBLE_EQ(element_b_matrix(sq, B), 6.0);
}

TEST(SolidGeometry, HexBMatrixIsVolumeDerivative) {
  double x[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  double B[8][3];
  EXPECT_NEAR(element_b_matrix(x, B), 1.0, 1e-15);
  for (int a = 0; a < 8; ++a)
    for (int d = 0; d < 3; ++d) x[a][d] += 0.2 * solid_test::hash_unit(a, d);
  check_element<3>(x);
}

TEST(SolidGeometry, HourglassVectorsAnnihilateLinearFields) {
  double x[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (int a = 0; a < 8; ++a)
    for (int d = 0; d < 3; ++d) x[a][d] += 0.15 * solid_test::hash_unit(a + 8, d);
  double B[8][3];
  const double V = element_b_matrix(x, B);
  for (int k = 0; k < 4; ++k) {
    const double* h = ElemTraits<3>::h[k];
    double hx[3] = {0, 0, 0};
    for (int a = 0; a < 8; ++a)
      for (int d = 0; d < 3; ++d) hx[d] += h[a] * x[a][d] / V;
    for (int i = 0; i < 3; ++i) {
      double sum = 0, sum1 = 0;
      for (int a = 0; a < 8; ++a) {
        const double g = h[a] - (hx[0] * B[a][0] + hx[1] * B[a][1] + hx[2] * B[a][2]);
        sum += g * x[a][i];
        sum1 += g;
      }
      EXPECT_NEAR(sum, 0.0, 1e-13);
      EXPECT_NEAR(sum1, 0.0, 1e-13);
    }
  }
}
