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

#include "solid_solver/forces/lanes.h"
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

// Elements are processed in batches of lanes::kLanes consecutive elements, one per vector lane; a batch
// at the end of the range repeats its last element in the unused lanes, which are never written back.
// Every branch of the scalar algorithm is a per-lane select, so each element gets the bits it would get
// alone. An element that fails (inverted, or a non-finite state) is not written back; the first failed
// element of the range is reported.
template <int D, class Eos, bool Strength>
void element_pass(const ElementPassArgs& A, const Eos& eos, int begin, int end, ElementPassResult& R) {
  using lanes::Lanes;
  constexpr int W = lanes::kLanes;
  constexpr int N = ElemTraits<D>::npe;
  constexpr int NH = ElemTraits<D>::nhg;
  constexpr double kD = D == 2 ? 1.0 : 2.0;
  const double dt = A.dt;
  const int batches = (end - begin + W - 1) / W;
  double dt_min = 1e300, ie_sum = 0.0;
  int bad = -1, bad_kind = 0;
#pragma omp parallel for schedule(static) reduction(min : dt_min) reduction(+ : ie_sum) if (end - begin > 4096)
  for (int bt = 0; bt < batches; ++bt) {
    const int z0 = begin + bt * W;
    const int nl = end - z0 < W ? end - z0 : W;  // live lanes
    std::ptrdiff_t zl[W], node[N][W];
    for (int l = 0; l < W; ++l) zl[l] = z0 + (l < nl ? l : nl - 1);
    for (int a = 0; a < N; ++a)
      for (int l = 0; l < W; ++l) node[a][l] = A.conn[zl[l] * N + a];
    // Gather: node coordinates and velocities, and the work of the previous corner forces.
    Lanes x[N][D], v[N][D];
    Lanes w{};
    {
      std::ptrdiff_t idx[W], fidx[W];
      for (int a = 0; a < N; ++a)
        for (int d = 0; d < D; ++d) {
          for (int l = 0; l < W; ++l) {
            idx[l] = node[a][l] * D + d;
            fidx[l] = zl[l] * (N * D) + a * D + d;
          }
          x[a][d] = lanes::gather(A.x, idx);
          v[a][d] = lanes::gather(A.v, idx);
          w += lanes::gather(A.fc, fidx) * lanes::gather(A.vbar, idx);
        }
    }
    auto load = [&](const double* p) {
      Lanes r;
      for (int l = 0; l < W; ++l) r[l] = p[zl[l]];
      return r;
    };
    // 1. compatible energy update
    const Lanes IE = load(A.ie) - dt * w;
    // 2. geometry
    Lanes B[N][D];
    const Lanes V = element_b_matrix(x, B);
    const auto upright = V > 0.0;  // a NaN volume fails too
    const Lanes Vold = load(A.vol);
    // 3.-4. kinematics and deviatoric stress
    Lanes divv;
    Lanes sz[6] = {};
    if constexpr (Strength) {
      Lanes xm[N][D], Bm[N][D];
      for (int a = 0; a < N; ++a)
        for (int d = 0; d < D; ++d) xm[a][d] = x[a][d] - 0.5 * dt * v[a][d];
      const Lanes Vm = element_b_matrix(xm, Bm);
      const Lanes iv = 1.0 / Vm;
      Lanes L[3][3] = {};
      for (int i = 0; i < D; ++i)
        for (int j = 0; j < D; ++j) {
          Lanes sum{};
          for (int a = 0; a < N; ++a) sum += v[a][i] * Bm[a][j];
          L[i][j] = sum * iv;
        }
      divv = L[0][0] + L[1][1] + L[2][2];
      {
        std::ptrdiff_t idx[W];
        for (int k = 0; k < 6; ++k) {
          for (int l = 0; l < W; ++l) idx[l] = zl[l] * 6 + k;
          sz[k] = lanes::gather(A.s, idx);
        }
      }
      const Lanes eps0 = load(A.eps_p);
      const Lanes deps =
          update_deviator(L, dt, A.strength.shear_modulus, A.strength.yield_stress, A.strength.hardening, eps0, sz);
      const Lanes eps1 = eps0 + deps;
      // Plastic work sigma_eq d eps_p V; after the return sigma_eq = Y0 + H eps_p (J2 flow).
      const Lanes wp = load(A.w_p) + (A.strength.yield_stress + A.strength.hardening * eps1) * deps * Vm;
      for (int l = 0; l < nl; ++l) {
        if (!upright[l]) continue;
        const std::ptrdiff_t z = zl[l];
        A.eps_p[z] = eps1[l];
        A.w_p[z] = wp[l];
        for (int k = 0; k < 6; ++k) A.s[z * 6 + k] = sz[k][l];
      }
    } else if (dt > 0.0) {
      divv = (V - Vold) / (dt * 0.5 * (V + Vold));
    } else {
      Lanes sum{};
      for (int a = 0; a < N; ++a)
        for (int d = 0; d < D; ++d) sum += v[a][d] * B[a][d];
      divv = sum / V;
    }
    // 5. EOS
    const Lanes M = load(A.emass);
    const Lanes rho = M / V;
    const Lanes e_pred = (IE - 0.5 * (load(A.p) + load(A.q)) * (V - Vold)) / M;
    Lanes P, c2;
    eos.eval(rho, e_pred, P, c2);
    P = P < A.p_min ? lanes::splat(A.p_min) : P;
    if constexpr (Strength) c2 += 4.0 * A.strength.shear_modulus / (3.0 * rho);
    const Lanes cs = lanes::sqrt(c2);
    // 6. artificial viscosity (compression only)
    Lanes Lq;
    if constexpr (D == 3) Lq = lanes::cbrt(V);
    else Lq = lanes::sqrt(V);
    const auto compressing = divv < 0.0;
    const Lanes ad = -divv;
    const Lanes lin = A.cq2 * Lq * ad + A.cl * cs;
    const Lanes Q = compressing ? rho * Lq * ad * lin : Lanes{};
    const Lanes b = compressing ? 2.0 * lin : Lanes{};
    // 7. stable step
    Lanes sb2{};
    for (int a = 0; a < N; ++a)
      for (int d = 0; d < D; ++d) sb2 += B[a][d] * B[a][d];
    const Lanes l_min = V / lanes::sqrt(kD * sb2);
    const Lanes dtz = l_min / (b + lanes::sqrt(b * b + c2));
    // 8. corner forces
    Lanes f[N][D];
    {
      const Lanes PQ = P + Q;
      const Lanes sig[3][3] = {{sz[0] - PQ, sz[3], sz[5]}, {sz[3], sz[1] - PQ, sz[4]}, {sz[5], sz[4], sz[2] - PQ}};
      for (int a = 0; a < N; ++a)
        for (int i = 0; i < D; ++i) {
          Lanes sum{};
          for (int j = 0; j < D; ++j) sum += sig[i][j] * B[a][j];
          f[a][i] = -sum;
        }
    }
    const auto sounding = cs > 0.0;
    if (A.kappa > 0.0 && lanes::any(sounding)) {
      const Lanes C = A.kappa * rho * cs * V / Lq;
      const Lanes iv = 1.0 / V;
      for (int k = 0; k < NH; ++k) {
        const double* h = ElemTraits<D>::h[k];
        Lanes hx[D];
        for (int d = 0; d < D; ++d) {
          Lanes sum{};
          for (int a = 0; a < N; ++a) sum += h[a] * x[a][d];
          hx[d] = sum * iv;
        }
        Lanes g[N];
        Lanes qk[D] = {};
        for (int a = 0; a < N; ++a) {
          Lanes dot{};
          for (int d = 0; d < D; ++d) dot += hx[d] * B[a][d];
          g[a] = h[a] - dot;
          for (int d = 0; d < D; ++d) qk[d] += v[a][d] * g[a];
        }
        for (int a = 0; a < N; ++a)
          for (int d = 0; d < D; ++d) f[a][d] = sounding ? f[a][d] - C * g[a] * qk[d] : f[a][d];
      }
    }
    // Write-back of the live, sound lanes, in element order.
    for (int l = 0; l < nl; ++l) {
      const int z = z0 + l;
      const int kind = !upright[l] ? 1 : (!(c2[l] >= 0.0) || !std::isfinite(P[l]) || !std::isfinite(IE[l])) ? 2 : 0;
      if (kind != 0) {
#pragma omp critical(solid_bad_element)
        if (bad < 0 || z < bad) {
          bad = z;
          bad_kind = kind;
        }
        continue;
      }
      if (dtz[l] < dt_min) dt_min = dtz[l];
      double* fz = A.fc + static_cast<std::ptrdiff_t>(z) * N * D;
      for (int a = 0; a < N; ++a)
        for (int d = 0; d < D; ++d) fz[a * D + d] = f[a][d][l];
      A.ie[z] = IE[l];
      ie_sum += IE[l];
      A.vol[z] = V[l];
      A.p[z] = P[l];
      A.q[z] = Q[l];
      A.c[z] = cs[l];
    }
  }
  if (dt_min < R.dt_min) R.dt_min = dt_min;
  R.ie_sum += ie_sum;
  if (bad >= 0 && (R.bad < 0 || bad < R.bad)) {
    R.bad = bad;
    R.bad_kind = bad_kind;
  }
}

}  // namespace cosim::solid
