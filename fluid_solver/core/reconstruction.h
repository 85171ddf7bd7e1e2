// MUSCL slope limiters (slopes are per cell, i.e. already multiplied by dx) and the low-Mach
// correction of reconstructed velocities (paper eqs. 10-11, Thornber et al. 2008; docs/methods.md §3).
#pragma once

#include <algorithm>
#include <cmath>

#include "fluid_solver/core/scene.h"

namespace cosim::fluid {

// Limited slope from the backward difference a = W_i - W_{i-1} and forward difference b = W_{i+1} - W_i.
// Written without branches so that the row loops vectorise.
template <Limiter LIM>
inline double limited_slope(double a, double b) {
  const double ab = a * b;
  double r;
  if constexpr (LIM == Limiter::Minmod) {
    r = std::abs(a) < std::abs(b) ? a : b;
  } else if constexpr (LIM == Limiter::VanLeer) {
    r = 2.0 * ab / (a + b);
  } else {  // monotonized central
    const double m = std::min(std::min(2.0 * std::abs(a), 2.0 * std::abs(b)), 0.5 * std::abs(a + b));
    r = a > 0 ? m : -m;
  }
  return ab > 0.0 ? r : 0.0;
}

// Paper eqs. 10-11: keep the mean of the two face velocities, scale their jump by
// z = min(1, max(M_L, M_R, cutoff)), with M the full-velocity Mach number of each side.
template <int DIM>
inline void low_mach_correction(double (&uL)[DIM], double cL, double (&uR)[DIM], double cR, double cutoff) {
  double qL = 0, qR = 0;
  for (int d = 0; d < DIM; ++d) {
    qL += uL[d] * uL[d];
    qR += uR[d] * uR[d];
  }
  const double M = std::max(std::sqrt(qL) / cL, std::sqrt(qR) / cR);
  const double z = std::min(1.0, std::max(M, cutoff));
  for (int d = 0; d < DIM; ++d) {
    const double mean = 0.5 * (uL[d] + uR[d]), half_jump = 0.5 * (uL[d] - uR[d]);
    uL[d] = mean + z * half_jump;
    uR[d] = mean - z * half_jump;
  }
}

}  // namespace cosim::fluid
