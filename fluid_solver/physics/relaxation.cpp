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
double alpha_of(const CellState2& s, int k) { return k == 0 ? s.alpha0 : 1.0 - s.alpha0; }
// Temperature from specific internal energy at density rho: e - q = cv T + pinf / rho (SG).
double temperature(const eos::StiffenedGas& e, double rho, double eint) { return (eint - e.q - e.pinf / rho) / e.cv; }
}  // namespace

void relax_velocity(CellState2& s, int dim) {
  const double M = s.m[0] + s.m[1];
  for (int d = 0; d < dim; ++d) {
    const double ueq = (s.mom[0][d] + s.mom[1][d]) / M;
    for (int k = 0; k < 2; ++k) {
      const double uk = s.mom[k][d] / s.m[k];
      s.E[k] += s.m[k] * ueq * (ueq - uk);
      s.mom[k][d] = s.m[k] * ueq;
    }
  }
}

double relax_pressure(CellState2& s, const eos::StiffenedGas (&eos)[2], int dim) {
  double A[2], a[2], b[2], pi[2], g[2], ke[2];
  for (int k = 0; k < 2; ++k) {
    g[k] = eos[k].gamma;
    pi[k] = eos[k].pinf;
    ke[k] = kinetic_per_mass(s, k, dim);
    A[k] = s.m[k] * (g[k] - 1.0) / g[k];
    a[k] = s.E[k] / s.m[k] - ke[k] - eos[k].q;  // e_k0 - q_k
    b[k] = alpha_of(s, k) / s.m[k];            // v_k0
  }
  // (1 - A0 b0 - A1 b1) p^2 + B p + C = 0 from sum_k m_k v_k(p) = 1 with
  // v_k(p) = (g_k - 1)(e_k0 - q_k + p v_k0) / (g_k (p + pinf_k)).
  const double qa = 1.0 - A[0] * b[0] - A[1] * b[1];
  const double qb = pi[0] + pi[1] - A[0] * (a[0] + b[0] * pi[1]) - A[1] * (a[1] + b[1] * pi[0]);
  const double qc = pi[0] * pi[1] - A[0] * a[0] * pi[1] - A[1] * a[1] * pi[0];
  const double disc = std::max(qb * qb - 4.0 * qa * qc, 0.0);
  const double sq = std::sqrt(disc);
  double p = qb > 0.0 ? 2.0 * qc / (-qb - sq) : (-qb + sq) / (2.0 * qa);  // larger root, no cancellation
  auto v_of = [&](int k, double pp) { return (g[k] - 1.0) * (a[k] + pp * b[k]) / (g[k] * (pp + pi[k])); };
  // One Newton step on f(p) = sum_k m_k v_k(p) - 1 removes the round-off of the closed form.
  {
    double f = -1.0, df = 0.0;
    for (int k = 0; k < 2; ++k) {
      f += s.m[k] * v_of(k, p);
      df += s.m[k] * (g[k] - 1.0) / g[k] * (b[k] * pi[k] - a[k]) / ((p + pi[k]) * (p + pi[k]));
    }
    if (df < 0.0 && std::isfinite(f / df)) p -= f / df;
  }
  const double pmin = -std::min(pi[0], pi[1]);
  if (!(p > pmin) || !std::isfinite(p)) return p;  // leave the state; the admissibility check reports it
  double alpha[2];
  for (int k = 0; k < 2; ++k) {
    const double v = v_of(k, p);
    alpha[k] = s.m[k] * v;
    const double e = a[k] + eos[k].q - p * (v - b[k]);
    s.E[k] = s.m[k] * (e + ke[k]);
  }
  s.alpha0 = alpha[0] / (alpha[0] + alpha[1]);
  return p;
}

void apply_drag(CellState2& s, const eos::StiffenedGas (&eos)[2], const Exchange& ex, int dim, double dt) {
  (void)eos;
  const double mg = s.m[0], mp = s.m[1], M = mg + mp;
  double du[3] = {0, 0, 0}, slip2 = 0;
  for (int d = 0; d < dim; ++d) {
    du[d] = s.mom[0][d] / mg - s.mom[1][d] / mp;
    slip2 += du[d] * du[d];
  }
  if (slip2 == 0.0) return;
  const double alpha_g = s.alpha0, alpha_p = 1.0 - s.alpha0;
  const double beta = drag_beta(ex.drag_law, alpha_p, mg / alpha_g, std::sqrt(slip2), ex.particle_diameter,
                                ex.gas_viscosity);
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
}

void apply_heat_transfer(CellState2& s, const eos::StiffenedGas (&eos)[2], const Exchange& ex, int dim, double dt) {
  const double mg = s.m[0], mp = s.m[1];
  const double rho_g = mg / s.alpha0, rho_p = mp / (1.0 - s.alpha0);
  const double eg = s.E[0] / mg - kinetic_per_mass(s, 0, dim);
  const double ep = s.E[1] / mp - kinetic_per_mass(s, 1, dim);
  const double dT = temperature(eos[0], rho_g, eg) - temperature(eos[1], rho_p, ep);
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
