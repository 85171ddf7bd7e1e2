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
void relax_row(int n, const TwoPhaseRow<DIM> r, const eos::StiffenedGas& e0, const eos::StiffenedGas& e1, double amin) {
#pragma GCC ivdep
  for (int i = 0; i < n; ++i) {
    double a = std::min(std::max(r.alpha[i], amin), 1.0 - amin);
    const double M0 = r.m[0][i], M1 = r.m[1][i];
    double en0 = r.E[0][i], en1 = r.E[1][i], k0 = 0.0, k1 = 0.0;
    double G = 0.0;  // the granular energy, E - kinetic - material
    if constexpr (GRAN) {
      double q = 0;
      for (int d = 0; d < DIM; ++d) q += r.mom[1][d][i] * r.mom[1][d][i];
      G = en1 - 0.5 * q / M1 - r.heat[i];
    }
    for (int d = 0; d < DIM; ++d) {
      double p0 = r.mom[0][d][i], p1 = r.mom[1][d][i];
      if constexpr (VRELAX) {  // mass-weighted mean velocity; kinetic energy lost becomes internal energy
        const double ueq = (p0 + p1) / (M0 + M1);
        en0 += M0 * ueq * (ueq - p0 / M0);
        en1 += M1 * ueq * (ueq - p1 / M1);
        p0 = M0 * ueq;
        p1 = M1 * ueq;
        r.mom[0][d][i] = p0;
        r.mom[1][d][i] = p1;
      }
      k0 += p0 * p0;
      k1 += p1 * p1;
    }
    if constexpr (PRELAX)  // the granular energy counts with the kinetic: the kernel sees the material's
      relax_pressure_kernel(a, M0, M1, 0.5 * k0 / (M0 * M0), 0.5 * k1 / (M1 * M1) + G / M1, en0, en1, e0, e1);
    if constexpr (GRAN) r.heat[i] = en1 - 0.5 * k1 / M1 - G;
    r.alpha[i] = a;
    r.E[0][i] = en0;
    r.E[1][i] = en1;
  }
}

}  // namespace cosim::fluid
