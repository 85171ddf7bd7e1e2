// Collision (compaction) stress of a dispersed particle phase (docs/methods.md §2.8): the force particles exert on
// each other and on walls when a cloud is packed, the mechanism by which a single-velocity particle field stops
// at a wall and rebounds from it. Form of Harris and Crighton (1994), used by Snider (2001):
//   Pi(alpha) = P_s alpha^beta / (alpha_cp - alpha)    for alpha <= alpha_a = alpha_cp - delta,
// continued linearly (value and slope of alpha_a) above alpha_a, so that the wave speed sqrt(Pi'(alpha) / rho_p)
// the explicit step must resolve stays bounded; Pi is a stress per mixture area (it acts on the particle phase).
#pragma once

#include <algorithm>
#include <cmath>

namespace cosim::fluid {

struct ParticleStress {
  double p_s = 1.0e7;    // [Pa]
  double beta = 3.0;     // exponent
  double packing = 0.6;  // close-packing volume fraction alpha_cp
  double delta = 0.01;   // the law is continued linearly within delta of packing
  // Faces where the particles are below this volume fraction on both sides, with no random motion, get neither
  // stress nor dissipation (a trace: Pi < 2e-8 Pa and c_Pi < 6e-4 m/s at 1e-5 with the defaults); 0: every face.
  double skip_below = 1e-5;

  // Pi and dPi/dalpha at volume fraction a; B > 0: the exponent is the integer B (pow costs a fifth of a step).
  template <int B = 0>
  [[gnu::always_inline]] inline void eval(double a, double& pi, double& dpi) const {
    const double aa = packing - delta, x = std::min(a, aa);
    double xb;
    if constexpr (B > 0) {
      xb = x;
      for (int i = 1; i < B; ++i) xb *= x;
    } else {
      xb = std::pow(x, beta);
    }
    const double gap = packing - x, base = p_s * xb / gap;
    const double slope = base * (beta / std::max(x, 1e-300) + 1.0 / gap);
    pi = base + slope * std::max(0.0, a - aa);
    dpi = slope;
  }
  // eval with the exponent known at compile time where it is the default 3 (the rows of the solver choose the
  // same way at the row level).
  void eval_any(double a, double& pi, double& dpi) const {
    if (beta == 3.0) eval<3>(a, pi, dpi);
    else eval<0>(a, pi, dpi);
  }
  double stress(double a) const {
    double pi, dpi;
    eval_any(a, pi, dpi);
    return pi;
  }
  // The speed of compaction waves in the particle phase of material density rho_p (B as in eval; wave_speed
  // chooses it as eval_any does).
  template <int B>
  [[gnu::always_inline]] inline double wave_speed_as(double a, double rho_p) const {
    double pi, dpi;
    eval<B>(a, pi, dpi);
    return std::sqrt(dpi / rho_p);
  }
  double wave_speed(double a, double rho_p) const {
    return beta == 3.0 ? wave_speed_as<3>(a, rho_p) : wave_speed_as<0>(a, rho_p);
  }
};

}  // namespace cosim::fluid
