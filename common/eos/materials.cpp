#include "common/eos/materials.h"

#include <cmath>

namespace cosim::eos {

StiffenedGas with_reference_temperature(StiffenedGas sg, double rho, double p, double T) {
  sg.a0 = (p + sg.pinf - (sg.gamma - 1.0) * rho * sg.cv * T) / std::pow(rho, sg.gamma);
  return sg;
}

namespace {

// Stiffened-gas fits of metals match the weak-shock slope and the reference sound speed
// (docs/methods.md §7.4: gamma = 4s - 1, pinf = rho0 c0^2 / gamma - p0); Mie-Grueneisen data from
// docs/methods.md §7.3 (Kinslow, Steinberg). Heat capacities are the table values. The metals' temperatures
// are fitted to their reference state (docs/methods.md §7.5); water's fit would give it a negative thermal
// expansion (its a0 < 0), so water keeps a0 = 0 and is given by its density.
std::vector<Material> build_library() {
  std::vector<Material> lib = {
      {"air", "ideal gas, gamma 1.4, R = 287.05 J/(kg K)", {1.4, 0.0, 0.0, 717.6}, 1.225, std::nullopt},
      {"water",
       "stiffened gas gamma 4.4, pinf 6e8 Pa (Saurel-Abgrall)",
       {4.4, 6.0e8, 0.0, 4186.0},
       1000.0,
       std::nullopt},
      {"tungsten",
       "stiffened-gas fit of W (gamma 3.948, pinf 7.904e10 Pa)",
       {3.948, 7.904e10, 0.0, 131.0},
       19224.0,
       MieGruneisenParams{19224.0, 4029.0, 1.237, 1.54, 131.0}},
      {"steel",
       "4340 steel, stiffened-gas fit (gamma 4.32, pinf 3.789e10 Pa)",
       {4.32, 3.789e10, 0.0, 448.0},
       7810.0,
       MieGruneisenParams{7810.0, 4578.0, 1.33, 1.67, 448.0}},
      {"ss304",
       "stainless steel 304, stiffened-gas fit (gamma 4.96, pinf 3.323e10 Pa)",
       {4.96, 3.323e10, 0.0, 441.3},
       7896.0,
       MieGruneisenParams{7896.0, 4569.0, 1.49, 2.17, 441.3}},
  };
  for (Material& m : lib)
    if (m.mg)
      m.sg = with_reference_temperature(m.sg, m.reference_density, m.reference_pressure, m.reference_temperature);
  return lib;
}

}  // namespace

const std::vector<Material>& material_library() {
  static const std::vector<Material> lib = build_library();
  return lib;
}

const Material* find_material(const std::string& name) {
  for (const auto& m : material_library())
    if (m.name == name) return &m;
  return nullptr;
}

std::vector<std::string> material_names() {
  std::vector<std::string> out;
  for (const auto& m : material_library()) out.push_back(m.name);
  return out;
}

}  // namespace cosim::eos
