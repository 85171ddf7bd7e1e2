#include "fluid_solver/physics/relaxation.h"

#include <algorithm>
#include <cmath>

#include "fluid_solver/physics/drag_laws.h"

namespace cosim::fluid {

namespace {
double kinetic_per_mass(const CellState2& s, int k, int dim) {
  double q = 0;
  for (int d = 0; d < dim; ++d) q += s.mom[k][d] * s.mom[k][d];
  return 0.5 * q / (s.m[k] * s.m[k]);
}
}  // namespace

double apply_drag(CellState2& s, const eos::StiffenedGas (&eos)[2], const Exchange& ex, int dim, double dt) {
  (void)eos;
  const double mg = s.m[0], mp = s.m[1], M = mg + mp;
  double du[3] = {0, 0, 0}, slip2 = 0;
  for (int d = 0; d < dim; ++d) {
    du[d] = s.mom[0][d] / mg - s.mom[1][d] / mp;
    slip2 += du[d] * du[d];
  }
  if (slip2 == 0.0) return 0.0;
  const double alpha_g = s.alpha0, alpha_p = 1.0 - s.alpha0;
  const double beta =
      drag_beta(ex.drag_law, alpha_p, mg / alpha_g, std::sqrt(slip2), ex.particle_diameter, ex.gas_viscosity);
  const double decay = std::exp(-dt * beta * (1.0 / mg + 1.0 / mp));
  const double ke_p_old = kinetic_per_mass(s, 1, dim) * mp;
  for (int d = 0; d < dim; ++d) {
    const double ueq = (s.mom[0][d] + s.mom[1][d]) / M;
    const double dnew = du[d] * decay;
    s.mom[0][d] = mg * (ueq + mp / M * dnew);
    s.mom[1][d] = mp * (ueq - mg / M * dnew);
  }
  const double dke_p = kinetic_per_mass(s, 1, dim) * mp - ke_p_old;
  s.E[1] += dke_p;
  s.E[0] -= dke_p;
  return beta;
}

void apply_heat_transfer(CellState2& s, const eos::StiffenedGas (&eos)[2], const Exchange& ex, int dim, double dt) {
  const double mg = s.m[0], mp = s.m[1];
  const double rho_g = mg / s.alpha0, rho_p = mp / (1.0 - s.alpha0);
  const double eg = s.E[0] / mg - kinetic_per_mass(s, 0, dim);
  const double ep = s.E[1] / mp - kinetic_per_mass(s, 1, dim);
  const double dT = eos[0].temperature_from_e(rho_g, eg) - eos[1].temperature_from_e(rho_p, ep);
  if (dT == 0.0) return;
  double slip2 = 0;
  for (int d = 0; d < dim; ++d) {
    const double du = s.mom[0][d] / mg - s.mom[1][d] / mp;
    slip2 += du * du;
  }
  const double K = heat_exchange_coefficient(1.0 - s.alpha0, rho_g, std::sqrt(slip2), ex.particle_diameter,
                                             ex.gas_viscosity, ex.gas_conductivity, eos[0].gamma * eos[0].cv);
  const double Cg = mg * eos[0].cv, Cp = mp * eos[1].cv;
  const double inv = 1.0 / Cg + 1.0 / Cp;
  const double Q = dT * (1.0 - std::exp(-dt * K * inv)) / inv;  // heat from gas to particles
  s.E[0] -= Q;
  s.E[1] += Q;
}

}  // namespace cosim::fluid
