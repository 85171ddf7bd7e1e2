// A small material library: named parameter sets for the EOS of the fluid (stiffened gas) and
// the structure (Mie-Grueneisen), docs/methods.md §7.1-7.4.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "common/eos/stiffened_gas.h"

namespace cosim::eos {

struct MieGruneisenParams {
  double rho0;    // [kg/m^3]
  double c0;      // bulk sound speed [m/s]
  double s;       // Us-up slope [-]
  double gamma0;  // Grueneisen coefficient [-]
  double cv;      // [J/(kg K)]
};

struct Material {
  std::string name;
  std::string description;
  StiffenedGas sg;                        // used by the fluid solver
  double reference_density;               // [kg/m^3] at the reference state
  std::optional<MieGruneisenParams> mg;   // metals only
  double reference_pressure = 1.0e5;      // [Pa]
  double reference_temperature = 293.15;  // [K]
};

// sg with its temperature datum a0 fitted so that T(rho, p) = T (stiffened_gas.h).
StiffenedGas with_reference_temperature(StiffenedGas sg, double rho, double p, double T);

const std::vector<Material>& material_library();
// Returns nullptr when the name is unknown.
const Material* find_material(const std::string& name);
std::vector<std::string> material_names();

}  // namespace cosim::eos
