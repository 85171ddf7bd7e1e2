// Stiffened-gas equation of state (numerics.md 7.2); the ideal gas is the case pinf = 0, q = 0.
//   p = (gamma-1) rho (e - q) - gamma pinf,  c^2 = gamma (p + pinf) / rho,
//   T = (p + pinf) / ((gamma-1) rho cv).
// A plain struct with inline functions: it is called in the innermost loops.
#pragma once

#include <cmath>

namespace cosim::eos {

struct StiffenedGas {
  double gamma = 1.4;
  double pinf = 0.0;  // [Pa]
  double q = 0.0;     // energy datum [J/kg]
  double cv = 717.6;  // [J/(kg K)]

  double pressure(double rho, double e) const { return (gamma - 1.0) * rho * (e - q) - gamma * pinf; }
  double internal_energy(double rho, double p) const { return (p + gamma * pinf) / ((gamma - 1.0) * rho) + q; }
  // Internal energy per unit volume rho*e.
  double rho_e(double rho, double p) const { return (p + gamma * pinf) / (gamma - 1.0) + rho * q; }
  double sound_speed_sq(double rho, double p) const { return gamma * (p + pinf) / rho; }
  double sound_speed(double rho, double p) const { return std::sqrt(sound_speed_sq(rho, p)); }
  double temperature(double rho, double p) const { return (p + pinf) / ((gamma - 1.0) * rho * cv); }
  double density_from_pT(double p, double T) const { return (p + pinf) / ((gamma - 1.0) * cv * T); }
  // rho and p admissible: rho > 0 and p + pinf > 0.
  bool admissible(double rho, double p) const { return rho > 0.0 && p + pinf > 0.0; }
};

}  // namespace cosim::eos
