#include "common/eos/materials.h"

namespace cosim::eos {

// Stiffened-gas fits of metals match the weak-shock slope and the reference sound speed
// (numerics.md 7.4: gamma = 4s - 1, pinf = rho0 c0^2 / gamma - p0); Mie-Grueneisen data from
// numerics.md 7.3 (Kinslow, Steinberg). Heat capacities are the table values.
const std::vector<Material>& material_library() {
  static const std::vector<Material> lib = {
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
