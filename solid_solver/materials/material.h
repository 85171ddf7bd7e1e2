// Material models of a block: an EOS for the pressure and an optional strength model.
// Plain structs with inline evaluation: they are called once per element per cycle, on one element
// (double) or on a batch of elements (lanes::Lanes), branch-free so that a batch gives the scalar bits.
#pragma once

#include <cmath>
#include <limits>
#include <string>

#include "solid_solver/forces/lanes.h"

namespace cosim::solid {

enum class EosKind { IdealGas, LinearElastic, MieGruneisen };

// Ideal gas (docs/methods.md §7.1): p = (gamma-1) rho e, c^2 = gamma p / rho.
struct IdealGasEos {
  double gamma;
  template <class T>
  void eval(T rho, T e, T& p, T& c2) const {
    p = (gamma - 1.0) * rho * e;
    c2 = gamma * lanes::max_zero(p) / rho;
  }
};

// Linear elastic bulk response: p = K (rho/rho_ref - 1), c^2 = K / rho_ref (energy independent).
struct LinearElasticEos {
  double bulk_modulus, rho_ref;
  template <class T>
  void eval(T rho, T /*e*/, T& p, T& c2) const {
    p = bulk_modulus * (rho / rho_ref - 1.0);
    c2 = lanes::like(rho, bulk_modulus / rho_ref);
  }
};

// Mie-Grueneisen with a linear Us-up Hugoniot (docs/methods.md §7.3), eta = 1 - rho0/rho:
//   p_H = rho0 c0^2 eta / (1 - s eta)^2 (compression), rho0 c0^2 eta (tension), e_H = p_H eta / (2 rho0),
//   p = p_H + Gamma0 rho0 (e - e_H),
//   c^2 = p_H' - Gamma0 rho0 e_H' + Gamma0 rho0 p / rho^2.
struct MieGruneisenEos {
  double rho0, c0, s, gamma0;
  template <class T>
  void eval(T rho, T e, T& p, T& c2) const {
    const T eta = 1.0 - rho0 / rho;
    const double k0 = rho0 * c0 * c0;
    const T deta = rho0 / (rho * rho);  // d eta / d rho
    // Both branches are evaluated and one is selected (compression or tension).
    const T den = 1.0 - s * eta;
    const T pH_c = k0 * eta / (den * den);
    const T dpH_c = k0 * (1.0 + s * eta) / (den * den * den) * deta;
    const T pH_t = k0 * eta;
    const T dpH_t = k0 * deta;
    const T pH = eta > 0.0 ? pH_c : pH_t;
    const T dpH = eta > 0.0 ? dpH_c : dpH_t;
    const T eH = pH * eta / (2.0 * rho0);
    const T deH = (dpH * eta + pH * deta) / (2.0 * rho0);
    const double g = gamma0 * rho0;
    p = pH + g * (e - eH);
    c2 = dpH - g * deH + g * p / (rho * rho);
  }
  // Specific internal energy at (rho, p).
  double energy(double rho, double p) const {
    double p0, c2;
    eval(rho, 0.0, p0, c2);
    return (p - p0) / (gamma0 * rho0);
  }
};

struct Strength {
  bool enabled = false;
  double shear_modulus = 0.0;  // G [Pa]
  double yield_stress = 0.0;   // Y0 [Pa]
  double hardening = 0.0;      // H [Pa]: Y = Y0 + H eps_p
};

struct MaterialModel {
  std::string library_name = "custom";
  EosKind eos = EosKind::IdealGas;
  IdealGasEos ideal{1.4};
  LinearElasticEos linear{0.0, 1.0};
  MieGruneisenEos mg{1.0, 1.0, 1.0, 1.0};
  double p_min = -std::numeric_limits<double>::infinity();  // pressure cut-off [Pa]
  Strength strength;
  double density = 1.0;  // initial density [kg/m^3]

  // Specific internal energy at (rho, p) (ideal gas and Mie-Grueneisen; 0 for linear elastic).
  double energy_from_pressure(double rho, double p) const {
    switch (eos) {
      case EosKind::IdealGas: return p / ((ideal.gamma - 1.0) * rho);
      case EosKind::MieGruneisen: return mg.energy(rho, p);
      case EosKind::LinearElastic: return 0.0;
    }
    return 0.0;
  }
  void eval(double rho, double e, double& p, double& c2) const {
    switch (eos) {
      case EosKind::IdealGas: ideal.eval(rho, e, p, c2); break;
      case EosKind::LinearElastic: linear.eval(rho, e, p, c2); break;
      case EosKind::MieGruneisen: mg.eval(rho, e, p, c2); break;
    }
  }
};

}  // namespace cosim::solid
