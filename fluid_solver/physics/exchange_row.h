// Drag (Akhatov-Vainshtein), heat exchange (Ranz-Marshall) and the granular temperature's losses over dt on a
// row of cells, on the conservative arrays directly (docs/methods.md §2.9, §6): the operators of apply_drag,
// apply_heat_transfer and GranularGas::after_collisions (physics/relaxation.cpp, granular.h), with the same
// formulas in the same order, so that a row gives bit for bit what the cell-by-cell loop gives. The vectorised
// passes hold the arithmetic; exp and pow, which have no vector form of the same bits, get short scalar passes of
// their own over the row's scratch arrays. Phase 0 is the gas, phase 1 the particles.
#pragma once

#include <algorithm>
#include <cmath>

#include "common/eos/stiffened_gas.h"
#include "fluid_solver/core/scene.h"
#include "fluid_solver/physics/two_phase_row.h"

namespace cosim::fluid {

// Scratch arrays a row needs: kExchangeScratch of n doubles each.
inline constexpr int kExchangeScratch = 8;

// DRAG: Akhatov-Vainshtein drag; HEAT: Ranz-Marshall heat exchange; GRAN: the particles carry a granular energy,
// kept apart from drag and heat exchange, and decaying by drag (at twice the slip's rate of the particles alone)
// and collisions.
template <int DIM, bool DRAG, bool HEAT, bool GRAN>
void exchange_row(int n, const TwoPhaseRow<DIM> r, const eos::StiffenedGas (&e)[2], const Exchange& ex, double dt,
                  double* scratch) {
  double* const decay = scratch;        // the slip's decay exponent, then its exp
  double* const gdecay = scratch + n;   // the granular energy's drag decay exponent, then its exp
  double* const G_s = scratch + 2 * n;  // granular energy per volume
  double* const pw0 = scratch + 3 * n;  // rho^(gamma-1) of the gas and the particles (temperature datum)
  double* const pw1 = scratch + 4 * n;
  double* const dT_s = scratch + 5 * n;    // T_g - T_p after drag
  double* const inv_s = scratch + 6 * n;   // 1/C_g + 1/C_p
  double* const hdecay = scratch + 7 * n;  // the temperature difference's decay exponent, then 1 - its exp
  const double d = ex.particle_diameter, mu = ex.gas_viscosity, kg = ex.gas_conductivity;
  const double cbrt_pr = std::cbrt(e[0].gamma * e[0].cv * mu / kg);  // Pr^(1/3) of the gas (Ranz-Marshall)

  // 1. Granular energy apart; the drag coefficient and the exponents of the slip's and the granular decay.
#pragma GCC ivdep
  for (int i = 0; i < n; ++i) {
    const double a0 = r.alpha[i], mg = r.m[0][i], mp = r.m[1][i];
    double G = 0.0;
    if constexpr (GRAN) {
      double q = 0;
      for (int k = 0; k < DIM; ++k) q += r.mom[1][k][i] * r.mom[1][k][i];
      G = r.E[1][i] - 0.5 * q / mp - r.heat[i];
      G_s[i] = G;
    }
    double beta = 0.0;
    if constexpr (DRAG) {
      double slip2 = 0;
      for (int k = 0; k < DIM; ++k) {
        const double du = r.mom[0][k][i] / mg - r.mom[1][k][i] / mp;
        slip2 += du * du;
      }
      const double alpha_g = a0, alpha_p = 1.0 - a0;
      const double Re = std::max(mg / alpha_g * std::sqrt(slip2) * d / mu, 0.0);
      // C_D Re of Akhatov-Vainshtein (drag_cd_re): dilute, dense, and blended between.
      const double ag = std::max(1.0 - alpha_p, 1e-6);
      const double dilute = 24.0 + 4.4 * std::sqrt(Re) + 0.42 * Re;
      const double dense = 4.0 / (3.0 * ag) * (1.75 * Re + 150.0 * alpha_p / ag);
      const double blend = ((alpha_p - 0.08) * dense + (0.45 - alpha_p) * dilute) / 0.37;
      const double cdre = alpha_p <= 0.08 ? dilute : (alpha_p >= 0.45 ? dense : blend);
      beta = slip2 == 0.0 ? 0.0 : 0.75 * alpha_p * mu * cdre / (d * d);
      decay[i] = -dt * beta * (1.0 / mg + 1.0 / mp);
    }
    if constexpr (GRAN) gdecay[i] = -2.0 * dt * beta / mp;
    if constexpr (HEAT) {
      pw0[i] = mg / a0;
      pw1[i] = mp / (1.0 - a0);
    }
  }
  // 2. exp and pow, scalar; exp(0) = 1 without the call (a cell without slip: the ambient of a blast).
  for (int i = 0; i < n; ++i) {
    if constexpr (DRAG) decay[i] = decay[i] == 0.0 ? 1.0 : std::exp(decay[i]);
    if constexpr (GRAN) gdecay[i] = gdecay[i] == 0.0 ? 1.0 : std::exp(gdecay[i]);
    if constexpr (HEAT) {
      pw0[i] = e[0].datum_power(pw0[i]);
      pw1[i] = e[1].datum_power(pw1[i]);
    }
  }
  // 3. The slip decays exactly over dt (apply_drag); the particles' kinetic energy change comes from the gas.
  //    Then the temperature difference and the heat exchange coefficient (apply_heat_transfer).
#pragma GCC ivdep
  for (int i = 0; i < n; ++i) {
    const double a0 = r.alpha[i], mg = r.m[0][i], mp = r.m[1][i];
    double e0 = r.E[0][i], e1 = r.E[1][i];
    if constexpr (GRAN) e1 -= G_s[i];
    double u0[DIM], u1[DIM];
    for (int k = 0; k < DIM; ++k) {
      u0[k] = r.mom[0][k][i];
      u1[k] = r.mom[1][k][i];
    }
    if constexpr (DRAG) {
      const double M = mg + mp, dec = decay[i];
      double kp_old = 0, kp_new = 0, slip2 = 0;
      double n0[DIM], n1[DIM];
      for (int k = 0; k < DIM; ++k) {
        kp_old += u1[k] * u1[k];
        const double du = u0[k] / mg - u1[k] / mp;
        slip2 += du * du;
        const double ueq = (u0[k] + u1[k]) / M;
        const double dnew = du * dec;
        n0[k] = mg * (ueq + mp / M * dnew);
        n1[k] = mp * (ueq - mg / M * dnew);
        kp_new += n1[k] * n1[k];
      }
      const double dke = 0.5 * kp_new / (mp * mp) * mp - 0.5 * kp_old / (mp * mp) * mp;
      const bool slip = slip2 != 0.0;  // without slip nothing changes (not even by round-off)
      for (int k = 0; k < DIM; ++k) {
        u0[k] = slip ? n0[k] : u0[k];
        u1[k] = slip ? n1[k] : u1[k];
        r.mom[0][k][i] = u0[k];
        r.mom[1][k][i] = u1[k];
      }
      e1 = slip ? e1 + dke : e1;
      e0 = slip ? e0 - dke : e0;
    }
    if constexpr (HEAT) {
      const double rho_g = mg / a0, rho_p = mp / (1.0 - a0);
      double k0 = 0, k1 = 0, slip2 = 0;
      for (int k = 0; k < DIM; ++k) {
        k0 += u0[k] * u0[k];
        k1 += u1[k] * u1[k];
        const double du = u0[k] / mg - u1[k] / mp;
        slip2 += du * du;
      }
      const double eg = e0 / mg - 0.5 * k0 / (mg * mg), ep = e1 / mp - 0.5 * k1 / (mp * mp);
      dT_s[i] = e[0].temperature_from_e(rho_g, eg, pw0[i]) - e[1].temperature_from_e(rho_p, ep, pw1[i]);
      const double Re = rho_g * std::sqrt(slip2) * d / mu;
      const double Nu = 2.0 + 0.6 * std::sqrt(Re) * cbrt_pr;
      const double K = 6.0 * (1.0 - a0) * kg * Nu / (d * d);
      const double inv = 1.0 / (mg * e[0].cv) + 1.0 / (mp * e[1].cv);
      inv_s[i] = inv;
      hdecay[i] = -dt * K * inv;
    }
    r.E[0][i] = e0;
    r.E[1][i] = e1;
  }
  // 4. exp, scalar, where the temperatures differ (step 5 leaves the others alone).
  if constexpr (HEAT)
    for (int i = 0; i < n; ++i) hdecay[i] = dT_s[i] == 0.0 ? 0.0 : 1.0 - std::exp(hdecay[i]);
  // 5. The heat from the gas to the particles; the granular energy back, less its losses (after_collisions).
  if constexpr (HEAT || GRAN) {
    const GranularGas& gr = ex.granular;
    const double coll = 8.0 * (1.0 - gr.restitution * gr.restitution);
    const double dsp = gr.diameter * std::sqrt(M_PI);
#pragma GCC ivdep
    for (int i = 0; i < n; ++i) {
      double e0 = r.E[0][i], e1 = r.E[1][i];
      if constexpr (HEAT) {
        const double dT = dT_s[i];
        const double Q = dT * hdecay[i] / inv_s[i];
        e0 = dT == 0.0 ? e0 : e0 - Q;
        e1 = dT == 0.0 ? e1 : e1 + Q;
      }
      if constexpr (GRAN) {
        e1 += G_s[i];
        const double a = 1.0 - r.alpha[i], mp = r.m[1][i];
        const double k = G_s[i] / mp * gdecay[i];
        const double c = coll * gr.g0(a) * a / dsp;
        const double s = std::sqrt(std::max(k, 0.0) * (2.0 / 3.0));
        const double q = 1.0 + 0.5 * c * s * dt;
        const double kc = a < gr.alpha_min ? 0.0 : (k > 0.0 ? k / (q * q) : k);
        double kin = 0;
        for (int j = 0; j < DIM; ++j) kin += r.mom[1][j][i] * r.mom[1][j][i];
        r.heat[i] = e1 - 0.5 * kin / mp - mp * kc;
      }
      r.E[0][i] = e0;
      r.E[1][i] = e1;
    }
  }
}

}  // namespace cosim::fluid
