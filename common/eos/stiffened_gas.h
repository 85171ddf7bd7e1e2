// Stiffened-gas equation of state (docs/methods.md §7.2); the ideal gas is the case pinf = 0, q = 0.
//   p = (gamma-1) rho (e - q) - gamma pinf,  c^2 = gamma (p + pinf) / rho,
//   T = (p + pinf - a0 rho^gamma) / ((gamma-1) rho cv).
// a0 = 0 is the usual temperature. A condensed material with its true heat capacity cv would then be far from
// its density at room temperature (tungsten: 35x), so its library entry fits a0 > 0 to the reference state
// (docs/methods.md §7.5): the entropy is s = cv ln(A - a0) with A = (p + pinf) / rho^gamma, which keeps the
// isentropes of the stiffened gas (the flow is unchanged), keeps cv, and puts T(rho_ref, p_ref) = T_ref.
// A plain struct with inline functions: it is called in the innermost loops.
#pragma once

#include <cmath>

namespace cosim::eos {

struct StiffenedGas {
  double gamma = 1.4;
  double pinf = 0.0;  // [Pa]
  double q = 0.0;     // energy datum [J/kg]
  double cv = 717.6;  // [J/(kg K)]
  double a0 = 0.0;    // temperature datum [Pa (m^3/kg)^gamma] (above); 0 for gases

  double pressure(double rho, double e) const { return (gamma - 1.0) * rho * (e - q) - gamma * pinf; }
  double internal_energy(double rho, double p) const { return (p + gamma * pinf) / ((gamma - 1.0) * rho) + q; }
  // Internal energy per unit volume rho*e.
  double rho_e(double rho, double p) const { return (p + gamma * pinf) / (gamma - 1.0) + rho * q; }
  double sound_speed_sq(double rho, double p) const { return gamma * (p + pinf) / rho; }
  double sound_speed(double rho, double p) const { return std::sqrt(sound_speed_sq(rho, p)); }
  double temperature(double rho, double p) const {
    const double cold = a0 == 0.0 ? 0.0 : a0 * std::pow(rho, gamma);
    return (p + pinf - cold) / ((gamma - 1.0) * rho * cv);
  }
  // The same from the specific internal energy: (e - q - pinf / rho - a0 rho^(gamma-1) / (gamma-1)) / cv.
  double temperature_from_e(double rho, double e) const { return temperature_from_e(rho, e, datum_power(rho)); }
  // rho^(gamma-1), the density factor of the temperature datum's energy (1 where a0 = 0, without pow), and the
  // temperature with it given: for row loops that take the power out of their vectorised part.
  double datum_power(double rho) const { return a0 == 0.0 ? 1.0 : std::pow(rho, gamma - 1.0); }
  double temperature_from_e(double rho, double e, double rho_gm1) const {
    const double cold = a0 == 0.0 ? 0.0 : a0 * rho_gm1 / (gamma - 1.0);
    return (e - q - pinf / rho - cold) / cv;
  }
  // The density at (p, T): the root of (gamma-1) cv T rho + a0 rho^gamma = p + pinf, unique for a0 >= 0 (the
  // left side increases with rho); Newton from the a0 = 0 density, which lies above it (the iteration decreases
  // monotonically, the function being convex). NaN where there is none (p + pinf <= 0 or T <= 0).
  double density_from_pT(double p, double T) const {
    const double P = p + pinf, k = (gamma - 1.0) * cv * T;
    if (!(P > 0.0) || !(k > 0.0)) return std::nan("");
    double rho = P / k;
    if (a0 <= 0.0) return rho;
    for (int it = 0; it < 100; ++it) {
      const double c = a0 * std::pow(rho, gamma);
      const double step = (k * rho + c - P) / (k + gamma * c / rho);
      rho -= step;
      if (std::abs(step) <= 1e-14 * rho) break;
    }
    return rho;
  }
  // rho and p admissible: rho > 0 and p + pinf > 0.
  bool admissible(double rho, double p) const { return rho > 0.0 && p + pinf > 0.0; }
};

}  // namespace cosim::eos
