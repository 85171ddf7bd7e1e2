// Initial conservative state from the scene: background, then regions in order (later ones
// win), or an analytic profile. The density wave is set to exact cell averages.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

#include "fluid_solver/core/grid.h"
#include "fluid_solver/core/layout.h"
#include "fluid_solver/core/scene.h"

namespace cosim::fluid {

MixtureValue profile_value(const FluidScene& scene, const std::array<double, 3>& x, const std::array<double, 3>& dx);

template <int DIM, int NP>
void set_initial_state(const FluidScene& scene, const Grid<DIM>& g, const eos::StiffenedGas (&eos)[NP], FieldArray& U) {
  using Lay = Layout<DIM, NP>;
  const double amin = NP == 2 ? scene.exchange.alpha_min : 0.0;
  for (int k3 = 0; k3 < g.n[2]; ++k3)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i) {
        const std::array<double, 3> x{g.center(0, i), DIM > 1 ? g.center(1, j) : 0.0, DIM > 2 ? g.center(2, k3) : 0.0};
        MixtureValue v = scene.background;
        for (const Region& r : scene.regions)
          if (r.contains(x, DIM)) v = r.value;
        if (scene.profile.kind != Profile::Kind::None) v = profile_value(scene, x, g.dx);
        const std::size_t c = g.index(i, j, k3);
        double alpha0 = 1.0;
        if constexpr (NP == 2) {
          alpha0 = std::clamp(v[0].alpha, amin, 1.0 - amin);
          U.var(Lay::alpha)[c] = alpha0;
        }
        for (int k = 0; k < NP; ++k) {
          const double a = k == 0 ? alpha0 : 1.0 - alpha0;
          const PhaseValue& pv = v[k];
          double q = 0;
          U.var(Lay::mass(k))[c] = a * pv.rho;
          for (int d = 0; d < DIM; ++d) {
            U.var(Lay::mom(k, d))[c] = a * pv.rho * pv.velocity[d];
            q += pv.velocity[d] * pv.velocity[d];
          }
          U.var(Lay::energy(k))[c] = a * (eos[k].rho_e(pv.rho, pv.p) + 0.5 * pv.rho * q);
        }
      }
}

}  // namespace cosim::fluid
