// One implicit step under the fluid's Robin condition (coupling.mode robin; docs/methods.md §4.4), shared by the
// interface nodes (simulation.cpp) and the rigid blocks' translation (rigid_body.cpp). The face pressure
// J + Z n . v_c at the velocity v_c = (1 - theta) v + theta v' of the step (v at its start, v' at its end; J the
// fluid's incoming characteristic), summed over the wetted faces with K = sum_f (A_f/k) Z_f n_f n_f^T and
// b = sum_f (A_f/k) Z_f v_sent,f n_f:
//   (m I + theta dt K) v' = m v_explicit + dt (b - (1 - theta) K v),
// where v_explicit = v + dt F/m already holds the face force at v_sent (face_pressure = J + Z v_sent).
#pragma once

#include <Eigen/Dense>

#include <algorithm>

namespace cosim::solid {

// theta = max(1/2, 1 - 1/r) for the ratio r = dt tr(K)/m of the impedance to the inertia (r = dt tr(I^-1 K_rot)
// for a rotation): centred (second order) while the fluid's impedance is small against the inertia, tending to
// backward Euler as it dominates (a light solid), where the amplification (1 - (1 - theta) r)/(1 + theta r) stays
// in [0, 1): no ringing, no growth. 1 when there is no impedance.
inline double robin_theta(double r) { return r > 0 ? std::max(0.5, 1.0 - 1.0 / r) : 1.0; }

// vn: v_explicit on entry (prescribed components, bit d of `fixed`, already at their value), v' on return;
// K row-major 3 x 3, b and v: D values. Returns theta. Without impedance (tr K = 0) vn is left as it is.
inline double robin_step(int D, double mass, double dt, unsigned fixed, const double* K, const double* b,
                         const double* v, double* vn) {
  double trace = 0.0;
  for (int i = 0; i < D; ++i) trace += K[4 * i];
  if (!(trace > 0)) return 1.0;
  const double theta = robin_theta(dt * trace / mass);
  Eigen::Matrix3d A = Eigen::Matrix3d::Identity();
  Eigen::Vector3d r = Eigen::Vector3d::Zero();
  for (int i = 0; i < D; ++i) {
    if (fixed & (1u << i)) {
      r[i] = vn[i];
      continue;
    }
    r[i] = mass * vn[i] + dt * b[i];
    A(i, i) = mass;
    for (int j = 0; j < D; ++j) {
      r[i] -= dt * (1.0 - theta) * K[3 * i + j] * v[j];
      if (fixed & (1u << j)) {
        r[i] -= dt * theta * K[3 * i + j] * vn[j];
      } else {
        A(i, j) += dt * theta * K[3 * i + j];
      }
    }
  }
  const Eigen::Vector3d x = A.ldlt().solve(r);
  for (int i = 0; i < D; ++i) vn[i] = x[i];
  return theta;
}

}  // namespace cosim::solid
