// The instantaneous relaxations of a row of cells (docs/methods.md §2.5), on the arrays directly so that the loop
// vectorises: the velocity relaxation to the mass-weighted mean velocity (VRELAX; the kinetic energy lost becomes
// internal energy) and the pressure relaxation of relax_pressure_kernel (PRELAX); alpha is first clamped to
// [alpha_min, 1 - alpha_min]. With a granular temperature (GRAN) the dispersed phase's granular energy is kept:
// what the relaxations exchange is its material's.
#pragma once

#include <algorithm>

#include "common/eos/stiffened_gas.h"
#include "fluid_solver/physics/relaxation.h"
#include "fluid_solver/physics/two_phase_row.h"

namespace cosim::fluid {

template <int DIM, bool VRELAX, bool PRELAX, bool GRAN>
void relax_row(int n, const TwoPhaseRow<DIM>& v, const eos::StiffenedGas& e0, const eos::StiffenedGas& e1,
               double amin) {
  double* const al = v.alpha;
  double* const m0 = v.m[0];
  double* const m1 = v.m[1];
  double* const E0 = v.E[0];
  double* const E1 = v.E[1];
  double* const H = v.heat;
  double *q0[DIM], *q1[DIM];
  for (int d = 0; d < DIM; ++d) {
    q0[d] = v.mom[0][d];
    q1[d] = v.mom[1][d];
  }
#pragma GCC ivdep
  for (int i = 0; i < n; ++i) {
    double a = std::min(std::max(al[i], amin), 1.0 - amin);
    const double M0 = m0[i], M1 = m1[i];
    double en0 = E0[i], en1 = E1[i], k0 = 0.0, k1 = 0.0;
    double G = 0.0;  // the granular energy, E - kinetic - material
    if constexpr (GRAN) {
      double q = 0;
      for (int d = 0; d < DIM; ++d) q += q1[d][i] * q1[d][i];
      G = en1 - 0.5 * q / M1 - H[i];
    }
    for (int d = 0; d < DIM; ++d) {
      double p0 = q0[d][i], p1 = q1[d][i];
      if constexpr (VRELAX) {  // mass-weighted mean velocity; kinetic energy lost becomes internal energy
        const double ueq = (p0 + p1) / (M0 + M1);
        en0 += M0 * ueq * (ueq - p0 / M0);
        en1 += M1 * ueq * (ueq - p1 / M1);
        p0 = M0 * ueq;
        p1 = M1 * ueq;
        q0[d][i] = p0;
        q1[d][i] = p1;
      }
      k0 += p0 * p0;
      k1 += p1 * p1;
    }
    if constexpr (PRELAX)  // the granular energy counts with the kinetic: the kernel sees the material's
      relax_pressure_kernel(a, M0, M1, 0.5 * k0 / (M0 * M0), 0.5 * k1 / (M1 * M1) + G / M1, en0, en1, e0, e1);
    if constexpr (GRAN) H[i] = en1 - 0.5 * k1 / M1 - G;
    al[i] = a;
    E0[i] = en0;
    E1[i] = en1;
  }
}

}  // namespace cosim::fluid
