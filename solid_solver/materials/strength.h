// Deviatoric stress update: hypo-elastic Jaumann rate with von Mises plasticity (Wilkins radial return).
// Stress components are stored as (xx, yy, zz, xy, yz, zx).
//   Objective rotation: s <- R s R^T with the Hughes-Winget (Cayley) increment R = (I - dt/2 W)^-1 (I + dt/2 W),
//   exactly orthogonal, so the invariants of s are kept to round-off under any rotation (Hughes & Winget,
//   IJNME 15 (1980) 1862). For a rigid rotation Q over the step with midpoint geometry, R = Q exactly.
//   Elastic trial: s <- s + 2 G dt dev(D).
//   Radial return (Wilkins 1964): sigma_eq = sqrt(3/2 s:s); if sigma_eq > Y: d eps_p = (sigma_eq - Y)/(3G + H),
//   Y <- Y + H d eps_p, s <- s Y / sigma_eq.
#pragma once

#include <cmath>

#include "solid_solver/forces/lanes.h"

namespace cosim::solid {

// L: velocity gradient (3x3, zero rows/cols for unused dimensions). s: deviator in/out. Returns plastic
// strain increment. T is double or a batch of elements (forces/lanes.h): the rotation and the return are
// computed for every lane and selected where they apply, which gives the bits of the branching form.
template <class T>
inline T update_deviator(const T (&L)[3][3], double dt, double G, double Y0, double H, T eps_p, T* s) {
  // Spin W = (L - L^T)/2 and its axial vector w (W v = w x v).
  const T w[3] = {0.5 * (L[2][1] - L[1][2]), 0.5 * (L[0][2] - L[2][0]), 0.5 * (L[1][0] - L[0][1])};
  // Cayley: with A = dt/2 W (axial a = dt/2 w), R = I + 2/(1+|a|^2) (A + A^2).
  const T a[3] = {0.5 * dt * w[0], 0.5 * dt * w[1], 0.5 * dt * w[2]};
  const T aa = a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
  T S[3][3] = {{s[0], s[3], s[5]}, {s[3], s[1], s[4]}, {s[5], s[4], s[2]}};
  {
    const T zero{};
    const T A[3][3] = {{zero, -a[2], a[1]}, {a[2], zero, -a[0]}, {-a[1], a[0], zero}};
    const T f = 2.0 / (1.0 + aa);
    T R[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        const T a2 = a[i] * a[j] - (i == j ? aa : zero);  // (A^2)_ij = a_i a_j - |a|^2 delta_ij
        R[i][j] = (i == j ? 1.0 : 0.0) + f * (A[i][j] + a2);
      }
    T Tm[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) Tm[i][j] = R[i][0] * S[0][j] + R[i][1] * S[1][j] + R[i][2] * S[2][j];
    const auto rotate = aa > 0.0;  // no spin: S unchanged
    for (int i = 0; i < 3; ++i)
      for (int j = i; j < 3; ++j) {
        const T r = Tm[i][0] * R[j][0] + Tm[i][1] * R[j][1] + Tm[i][2] * R[j][2];
        S[i][j] = rotate ? r : S[i][j];
      }
    S[1][0] = S[0][1];
    S[2][0] = S[0][2];
    S[2][1] = S[1][2];
  }
  const T tr = (L[0][0] + L[1][1] + L[2][2]) / 3.0;
  const double g2 = 2.0 * G * dt;
  s[0] = S[0][0] + g2 * (L[0][0] - tr);
  s[1] = S[1][1] + g2 * (L[1][1] - tr);
  s[2] = S[2][2] + g2 * (L[2][2] - tr);
  s[3] = S[0][1] + G * dt * (L[0][1] + L[1][0]);
  s[4] = S[1][2] + G * dt * (L[1][2] + L[2][1]);
  s[5] = S[0][2] + G * dt * (L[0][2] + L[2][0]);
  // Remove round-off trace.
  const T t3 = (s[0] + s[1] + s[2]) / 3.0;
  s[0] -= t3;
  s[1] -= t3;
  s[2] -= t3;
  const T j2x2 = s[0] * s[0] + s[1] * s[1] + s[2] * s[2] + 2.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]);
  const T seq = lanes::sqrt(1.5 * j2x2);
  const T Y = Y0 + H * eps_p;
  const auto yielded = seq > Y;
  const T deps = yielded ? (seq - Y) / (3.0 * G + H) : T{};
  const T scale = (Y + H * deps) / seq;
  for (int k = 0; k < 6; ++k) s[k] = yielded ? s[k] * scale : s[k];
  return deps;
}

inline double von_mises(const double* s) {
  return std::sqrt(1.5 * (s[0] * s[0] + s[1] * s[1] + s[2] * s[2] + 2.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5])));
}

}  // namespace cosim::solid
