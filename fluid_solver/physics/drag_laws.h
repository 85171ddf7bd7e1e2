// Gas-particle exchange closures (docs/methods.md §6). Drag enters as the momentum exchange
// coefficient beta [kg m^-3 s^-1] with F_on_particles = beta (u_g - u_p), and
//   beta = 3/4 C_D alpha_p rho_g |du| / d = 3/4 alpha_p mu_g (C_D Re) / d^2,
// written with C_D Re so that the Stokes limit Re -> 0 stays finite.
#pragma once

#include <algorithm>
#include <cmath>

#include "fluid_solver/core/scene.h"

namespace cosim::fluid {

// C_D * Re for a sphere at particle Reynolds number Re and particle volume fraction alpha_p.
inline double drag_cd_re(DragLaw law, double Re, double alpha_p) {
  Re = std::max(Re, 0.0);
  switch (law) {
    case DragLaw::SchillerNaumann:  // Schiller & Naumann (1933)
      return Re < 1000.0 ? 24.0 * (1.0 + 0.15 * std::pow(Re, 0.687)) : 0.44 * Re;
    case DragLaw::CliftGauvin:  // Clift & Gauvin (1970), docs/methods.md §6.2
      return 24.0 * (1.0 + 0.15 * std::pow(Re, 0.687)) +
             (Re > 0 ? 0.42 * Re / (1.0 + 42500.0 * std::pow(Re, -1.16)) : 0.0);
    case DragLaw::AkhatovVainshtein: {
      // Akhatov & Vainshtein (1984) as quoted in later work (constants unverified, docs/methods.md §6.4): dilute
      // 24/Re + 4.4/sqrt(Re) + 0.42 for alpha_p <= 0.08, Ergun-type 4/(3 alpha_g)(1.75 + 150 alpha_p /
      // (alpha_g Re)) for alpha_p >= 0.45, linear blend in alpha_p between.
      const double ag = std::max(1.0 - alpha_p, 1e-6);
      const double dilute = 24.0 + 4.4 * std::sqrt(Re) + 0.42 * Re;
      const double dense = 4.0 / (3.0 * ag) * (1.75 * Re + 150.0 * alpha_p / ag);
      if (alpha_p <= 0.08) return dilute;
      if (alpha_p >= 0.45) return dense;
      return ((alpha_p - 0.08) * dense + (0.45 - alpha_p) * dilute) / 0.37;
    }
  }
  return 0.0;
}

inline double drag_beta(DragLaw law, double alpha_p, double rho_g, double slip, double d, double mu_g) {
  const double Re = rho_g * slip * d / mu_g;
  return 0.75 * alpha_p * mu_g * drag_cd_re(law, Re, alpha_p) / (d * d);
}

// Ranz & Marshall (1952): Nu = 2 + 0.6 Re^1/2 Pr^1/3; volumetric coefficient K = 6 alpha_p k_g Nu / d^2.
inline double heat_exchange_coefficient(double alpha_p, double rho_g, double slip, double d, double mu_g, double k_g,
                                        double cp_g) {
  const double Re = rho_g * slip * d / mu_g;
  const double Pr = cp_g * mu_g / k_g;
  const double Nu = 2.0 + 0.6 * std::sqrt(Re) * std::cbrt(Pr);
  return 6.0 * alpha_p * k_g * Nu / (d * d);
}

}  // namespace cosim::fluid
