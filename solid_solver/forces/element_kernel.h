// The element pass of one cycle, for one block (one material), templated on the dimension, the EOS and
// whether the block has strength, so that the inner loop has no branches on the material.
// Per element z, in order:
//  1. compatible energy update: IE_z -= dt sum_a f_za . vbar_a with the corner forces f_za of the previous
//     pass (pressure, deviator, viscosity and hourglass together), so that sum(IE) + KE changes only by the
//     work of boundary forces (Caramana, Burton, Shashkov, Whalen, JCP 146 (1998) 227);
//  2. geometry at x^{n+1} (element_geometry.h);
//  3. velocity gradient from v^{n+1/2} with midpoint geometry (strength), or div v from the volume change;
//  4. deviator: Jaumann/Hughes-Winget rotation, elastic trial, radial return (strength.h);
//  5. EOS at rho = M/V and the energy extrapolated to t^{n+1}: IE - (p+q)(V^{n+1}-V^n)/2 (the stored IE
//     stays the compatible one, so conservation is unaffected);
//  6. artificial viscosity, compression only: q = rho L (C_q^2 L |div v| + C_l c) |div v|, L = V^(1/D);
//  7. stable step (Wilkins): dt_z = l / (b + sqrt(b^2 + c^2)), b = 2 (C_q^2 L |div v| + C_l c),
//     l = (sum_i 1/h_i^2)^(-1/2) estimated as V / sqrt(k_D sum_a |B_a|^2), k_2 = 1, k_3 = 2;
//  8. corner forces f_a = -sigma B_a with sigma = s - (p+q) I, plus FB viscous hourglass forces
//     f_a = -C sum_k Gamma_ak (sum_b v_b Gamma_bk), C = kappa rho c V^((D-1)/D).
#pragma once

#include <omp.h>

#include <cmath>

#include "solid_solver/kinematics/element_geometry.h"
#include "solid_solver/materials/material.h"
#include "solid_solver/materials/strength.h"

namespace cosim::solid {

struct ElementPassArgs {
  const int* conn;
  const double* x;
  const double* v;
  const double* vbar;
  const double* emass;
  double* vol;
  double* ie;
  double* p;
  double* q;
  double* c;
  double* s;
  double* eps_p;
  double* w_p;
  double* fc;
  double dt;
  double cq2, cl, kappa, p_min;
  Strength strength;
};

struct ElementPassResult {
  double dt_min = 1e300;  // stable step before the safety factor [s]
  double ie_sum = 0.0;    // [J]
  int bad = -1;           // first failed element, -1 if none
  int bad_kind = 0;       // 1 inverted, 2 non-finite state
};

template <int D, class Eos, bool Strength>
void element_pass(const ElementPassArgs& A, const Eos& eos, int begin, int end, ElementPassResult& R) {
  constexpr int N = ElemTraits<D>::npe;
  constexpr int NH = ElemTraits<D>::nhg;
  constexpr double kD = D == 2 ? 1.0 : 2.0;
  const double dt = A.dt;
  double dt_min = 1e300, ie_sum = 0.0;
  int bad = -1, bad_kind = 0;
#pragma omp parallel for schedule(static) reduction(min : dt_min) reduction(+ : ie_sum) if (end - begin > 4096)
  for (int z = begin; z < end; ++z) {
    const int* cn = A.conn + static_cast<std::ptrdiff_t>(z) * N;
    double x[N][D], v[N][D];
    double* f = A.fc + static_cast<std::ptrdiff_t>(z) * N * D;
    double w = 0.0;
    for (int a = 0; a < N; ++a) {
      const std::ptrdiff_t o = static_cast<std::ptrdiff_t>(cn[a]) * D;
      for (int d = 0; d < D; ++d) {
        x[a][d] = A.x[o + d];
        v[a][d] = A.v[o + d];
        w += f[a * D + d] * A.vbar[o + d];
      }
    }
    // 1. compatible energy update
    const double IE = A.ie[z] - dt * w;
    // 2. geometry
    double B[N][D];
    const double V = element_b_matrix(x, B);
    if (!(V > 0.0)) {
#pragma omp critical(solid_bad_element)
      if (bad < 0 || z < bad) {
        bad = z;
        bad_kind = 1;
      }
      continue;
    }
    const double Vold = A.vol[z];
    // 3.-4. kinematics and deviatoric stress
    double divv;
    double sz[6] = {0, 0, 0, 0, 0, 0};
    if constexpr (Strength) {
      double xm[N][D], Bm[N][D];
      for (int a = 0; a < N; ++a)
        for (int d = 0; d < D; ++d) xm[a][d] = x[a][d] - 0.5 * dt * v[a][d];
      const double Vm = element_b_matrix(xm, Bm);
      const double iv = 1.0 / Vm;
      double L[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
      for (int i = 0; i < D; ++i)
        for (int j = 0; j < D; ++j) {
          double sum = 0.0;
          for (int a = 0; a < N; ++a) sum += v[a][i] * Bm[a][j];
          L[i][j] = sum * iv;
        }
      divv = L[0][0] + L[1][1] + L[2][2];
      double* sp = A.s + static_cast<std::ptrdiff_t>(z) * 6;
      for (int k = 0; k < 6; ++k) sz[k] = sp[k];
      const double deps = update_deviator(L, dt, A.strength.shear_modulus, A.strength.yield_stress,
                                          A.strength.hardening, A.eps_p[z], sz);
      A.eps_p[z] += deps;
      // Plastic work sigma_eq d eps_p V; after the return sigma_eq = Y0 + H eps_p (J2 flow).
      A.w_p[z] += (A.strength.yield_stress + A.strength.hardening * A.eps_p[z]) * deps * Vm;
      for (int k = 0; k < 6; ++k) sp[k] = sz[k];
    } else if (dt > 0.0) {
      divv = (V - Vold) / (dt * 0.5 * (V + Vold));
    } else {
      double sum = 0.0;
      for (int a = 0; a < N; ++a)
        for (int d = 0; d < D; ++d) sum += v[a][d] * B[a][d];
      divv = sum / V;
    }
    // 5. EOS
    const double M = A.emass[z];
    const double rho = M / V;
    const double e_pred = (IE - 0.5 * (A.p[z] + A.q[z]) * (V - Vold)) / M;
    double P, c2;
    eos.eval(rho, e_pred, P, c2);
    if (P < A.p_min) P = A.p_min;
    if constexpr (Strength) c2 += 4.0 * A.strength.shear_modulus / (3.0 * rho);
    if (!(c2 >= 0.0) || !std::isfinite(P) || !std::isfinite(IE)) {
#pragma omp critical(solid_bad_element)
      if (bad < 0 || z < bad) {
        bad = z;
        bad_kind = 2;
      }
      continue;
    }
    const double cs = std::sqrt(c2);
    // 6. artificial viscosity
    const double Lq = D == 3 ? std::cbrt(V) : std::sqrt(V);
    double Q = 0.0, b = 0.0;
    if (divv < 0.0) {
      const double ad = -divv;
      const double lin = A.cq2 * Lq * ad + A.cl * cs;
      Q = rho * Lq * ad * lin;
      b = 2.0 * lin;
    }
    // 7. stable step
    double sb2 = 0.0;
    for (int a = 0; a < N; ++a)
      for (int d = 0; d < D; ++d) sb2 += B[a][d] * B[a][d];
    const double l = V / std::sqrt(kD * sb2);
    const double dtz = l / (b + std::sqrt(b * b + c2));
    if (dtz < dt_min) dt_min = dtz;
    // 8. corner forces
    double sig[3][3] = {{sz[0], sz[3], sz[5]}, {sz[3], sz[1], sz[4]}, {sz[5], sz[4], sz[2]}};
    for (int d = 0; d < 3; ++d) sig[d][d] -= P + Q;
    for (int a = 0; a < N; ++a)
      for (int i = 0; i < D; ++i) {
        double sum = 0.0;
        for (int j = 0; j < D; ++j) sum += sig[i][j] * B[a][j];
        f[a * D + i] = -sum;
      }
    if (A.kappa > 0.0 && cs > 0.0) {
      const double C = A.kappa * rho * cs * V / Lq;
      const double iv = 1.0 / V;
      for (int k = 0; k < NH; ++k) {
        const double* h = ElemTraits<D>::h[k];
        double hx[D];
        for (int d = 0; d < D; ++d) {
          double sum = 0.0;
          for (int a = 0; a < N; ++a) sum += h[a] * x[a][d];
          hx[d] = sum * iv;
        }
        double g[N];
        double qk[D] = {};
        for (int a = 0; a < N; ++a) {
          double dot = 0.0;
          for (int d = 0; d < D; ++d) dot += hx[d] * B[a][d];
          g[a] = h[a] - dot;
          for (int d = 0; d < D; ++d) qk[d] += v[a][d] * g[a];
        }
        for (int a = 0; a < N; ++a)
          for (int d = 0; d < D; ++d) f[a * D + d] -= C * g[a] * qk[d];
      }
    }
    A.ie[z] = IE;
    ie_sum += IE;
    A.vol[z] = V;
    A.p[z] = P;
    A.q[z] = Q;
    A.c[z] = cs;
  }
  if (dt_min < R.dt_min) R.dt_min = dt_min;
  R.ie_sum += ie_sum;
  if (bad >= 0 && (R.bad < 0 || bad < R.bad)) {
    R.bad = bad;
    R.bad_kind = bad_kind;
  }
}

}  // namespace cosim::solid
