// One-point element geometry (Flanagan & Belytschko, IJNME 17 (1981) 679, "uniform strain" element):
//   B_a = integral over the element of grad N_a dV = dV/dx_a  (exact for bilinear quads / trilinear hexes),
//   V = (1/D) sum_a B_a . x_a  (V is homogeneous of degree D in the coordinates),
//   velocity gradient L_ij = (1/V) sum_a v_ia B_ja  (exact for linear velocity fields on any shape).
// 2D: B_a = 1/2 (y_{a+1} - y_{a-1}, x_{a-1} - x_{a+1}) for counter-clockwise nodes 0..3.
// 3D: B_a = surface integral of N_a n dA over the three faces touching node a. For a bilinear face p1..p4
//   (counter-clockwise seen from outside, local coords (-,-),(+,-),(+,+),(-,+)) with
//   g1 = -p1+p2+p3-p4, g2 = -p1-p2+p3+p4, h = p1-p2+p3-p4, the exact integral of N_i n dA is
//   (1/16) [g1 x g2 + (xi_i/3) g1 x h + (eta_i/3) h x g2]   (x_xi x x_eta is linear in xi, eta).
// Hourglass base vectors (FB eq. 57): Gamma_ak = h_ak - (1/V) (sum_b h_bk x_b) . B_a, orthogonal to every
// linear field, so hourglass forces vanish for uniform strain and rigid motion.
#pragma once

namespace cosim::solid {

template <int D>
struct ElemTraits;
template <>
struct ElemTraits<2> {
  static constexpr int npe = 4;
  static constexpr int nhg = 1;
  static constexpr double h[1][4] = {{1, -1, 1, -1}};
};
template <>
struct ElemTraits<3> {
  static constexpr int npe = 8;
  static constexpr int nhg = 4;
  // xi*eta, eta*zeta, zeta*xi, xi*eta*zeta at the VTK hex nodes.
  static constexpr double h[4][8] = {{1, -1, 1, -1, 1, -1, 1, -1},
                                     {1, 1, -1, -1, -1, -1, 1, 1},
                                     {1, -1, -1, 1, -1, 1, 1, -1},
                                     {-1, 1, -1, 1, 1, -1, 1, -1}};
};

// Computes B[a][d] and returns the volume (area x unit thickness in 2D). T is double or a batch of elements
// (forces/lanes.h), with the same operations in the same order either way.
template <class T>
inline T element_b_matrix(const T (&x)[4][2], T (&B)[4][2]) {
  for (int a = 0; a < 4; ++a) {
    const int an = (a + 1) & 3, ap = (a + 3) & 3;
    B[a][0] = 0.5 * (x[an][1] - x[ap][1]);
    B[a][1] = 0.5 * (x[ap][0] - x[an][0]);
  }
  // Shoelace: A = 1/2 [(x2-x0)(y3-y1) - (x3-x1)(y2-y0)]
  return 0.5 * ((x[2][0] - x[0][0]) * (x[3][1] - x[1][1]) - (x[3][0] - x[1][0]) * (x[2][1] - x[0][1]));
}

template <class T>
inline T element_b_matrix(const T (&x)[8][3], T (&B)[8][3]) {
  static constexpr int face[6][4] = {{0, 4, 7, 3}, {1, 2, 6, 5}, {0, 1, 5, 4},
                                     {3, 7, 6, 2}, {0, 3, 2, 1}, {4, 5, 6, 7}};
  static constexpr double fxi[4] = {-1, 1, 1, -1}, feta[4] = {-1, -1, 1, 1};
  for (int a = 0; a < 8; ++a) B[a][0] = B[a][1] = B[a][2] = T{};
  for (int f = 0; f < 6; ++f) {
    const T* p1 = x[face[f][0]];
    const T* p2 = x[face[f][1]];
    const T* p3 = x[face[f][2]];
    const T* p4 = x[face[f][3]];
    T g1[3], g2[3], h[3];
    for (int d = 0; d < 3; ++d) {
      g1[d] = -p1[d] + p2[d] + p3[d] - p4[d];
      g2[d] = -p1[d] - p2[d] + p3[d] + p4[d];
      h[d] = p1[d] - p2[d] + p3[d] - p4[d];
    }
    const T c0[3] = {g1[1] * g2[2] - g1[2] * g2[1], g1[2] * g2[0] - g1[0] * g2[2], g1[0] * g2[1] - g1[1] * g2[0]};
    const T c1[3] = {g1[1] * h[2] - g1[2] * h[1], g1[2] * h[0] - g1[0] * h[2], g1[0] * h[1] - g1[1] * h[0]};
    const T c2[3] = {h[1] * g2[2] - h[2] * g2[1], h[2] * g2[0] - h[0] * g2[2], h[0] * g2[1] - h[1] * g2[0]};
    for (int i = 0; i < 4; ++i) {
      T* b = B[face[f][i]];
      const double s1 = fxi[i] * (1.0 / 3.0), s2 = feta[i] * (1.0 / 3.0);
      for (int d = 0; d < 3; ++d) b[d] += 0.0625 * (c0[d] + s1 * c1[d] + s2 * c2[d]);
    }
  }
  T v{};
  for (int a = 0; a < 8; ++a) v += B[a][0] * x[a][0] + B[a][1] * x[a][1] + B[a][2] * x[a][2];
  return v * (1.0 / 3.0);
}

}  // namespace cosim::solid
