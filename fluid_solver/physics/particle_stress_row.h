// A dispersed phase's collision stress Pi(alpha) at the faces of a row (docs/methods.md §2.8): the centred stress in
// its normal momentum and energy fluxes, with the local Lax-Friedrichs dissipation of its compaction waves,
// -c_f/2 (U+ - U-), c_f = max of the two sides' sqrt(Pi'/rho_p), on its conserved variables. GRAN: the granular
// pressure joins the stress, the granular gas's sound its wave speed, and the material energy gets the same
// dissipation (§2.9). D: the faces' normal direction; B: the stress's integer exponent (0: any, by pow).
#pragma once

#include <algorithm>
#include <cmath>

#include "common/eos/stiffened_gas.h"
#include "fluid_solver/physics/granular.h"
#include "fluid_solver/physics/particle_stress.h"

namespace cosim::fluid {

// The dispersed phase's reconstructed states on the two sides of a row's faces (alpha is the carrier's, phase 0;
// k the granular energy per mass, GRAN only) and the flux arrays its stress adds to.
template <int DIM>
struct DispersedFaceRow {
  const double *alpha_left = nullptr, *alpha_right = nullptr;
  const double *rho_left = nullptr, *rho_right = nullptr, *p_left = nullptr, *p_right = nullptr;
  const double* u_left[DIM] = {};
  const double* u_right[DIM] = {};
  const double *k_left = nullptr, *k_right = nullptr;
  double* flux_mass = nullptr;
  double* flux_mom[DIM] = {};
  double* flux_energy = nullptr;
  double* flux_heat = nullptr;

  // The same views from face `n` on.
  void advance(int n) {
    for (const double** p : {&alpha_left, &alpha_right, &rho_left, &rho_right, &p_left, &p_right}) *p += n;
    for (int d = 0; d < DIM; ++d) {
      u_left[d] += n;
      u_right[d] += n;
      flux_mom[d] += n;
    }
    if (k_left) k_left += n;
    if (k_right) k_right += n;
    flux_mass += n;
    flux_energy += n;
    if (flux_heat) flux_heat += n;
  }
};

// Random energy per mass [J/kg] below which a particle trace counts as still (a random speed of 1 mm/s; round-off
// of E - e - u^2/2 is about 1e-11).
inline constexpr double kRandomEnergyOfATrace = 1e-6;

template <int DIM, int D, int B, bool GRAN>
void add_particle_stress_row(int len, const DispersedFaceRow<DIM>& r, const ParticleStress& ps, const GranularGas& gr,
                             const eos::StiffenedGas& e) {
  const double ig1 = 1.0 / (e.gamma - 1.0), gpinf = e.gamma * e.pinf, q = e.q;
  const double *al = r.alpha_left, *ar = r.alpha_right;
  const double *rL = r.rho_left, *rR = r.rho_right, *pL = r.p_left, *pR = r.p_right;
  const double *uL[DIM], *uR[DIM];
  double* fmom[DIM];
  for (int d = 0; d < DIM; ++d) {
    uL[d] = r.u_left[d];
    uR[d] = r.u_right[d];
    fmom[d] = r.flux_mom[d];
  }
  double* const fm = r.flux_mass;
  double* const fe = r.flux_energy;
  const double *gL = r.k_left, *gR = r.k_right;
  double* const fh = r.flux_heat;
#pragma GCC ivdep
  for (int f = 0; f < len; ++f) {
    const double aL = 1.0 - al[f], aR = 1.0 - ar[f];
    double piL, dL, piR, dR;
    ps.eval<B>(aL, piL, dL);
    ps.eval<B>(aR, piR, dR);
    double cf = std::sqrt(std::max(dL / rL[f], dR / rR[f]));
    double gEL = 0.0, gER = 0.0;  // granular energy per volume of the two edges
    if constexpr (GRAN) {
      double pgL, cgL, pgR, cgR;
      gr.pressure_and_speed(aL, rL[f], gL[f], pgL, cgL);
      gr.pressure_and_speed(aR, rR[f], gR[f], pgR, cgR);
      piL += pgL;
      piR += pgR;
      cf = std::max(cf, std::max(cgL, cgR));
      gEL = aL * rL[f] * gL[f];
      gER = aR * rR[f] * gR[f];
    } else {
      (void)gr, (void)gL, (void)gR, (void)fh;
    }
    const double mL = aL * rL[f], mR = aR * rR[f];
    double kL = 0, kR = 0;
    for (int d = 0; d < DIM; ++d) {
      kL += uL[d][f] * uL[d][f];
      kR += uR[d][f] * uR[d][f];
      fmom[d][f] -= 0.5 * cf * (mR * uR[d][f] - mL * uL[d][f]);
    }
    fmom[D][f] += 0.5 * (piL + piR);
    fm[f] -= 0.5 * cf * (mR - mL);
    const double hL = aL * ((pL[f] + gpinf) * ig1 + rL[f] * q), hR = aR * ((pR[f] + gpinf) * ig1 + rR[f] * q);
    const double EL = hL + aL * 0.5 * rL[f] * kL + gEL, ER = hR + aR * 0.5 * rR[f] * kR + gER;
    fe[f] += 0.5 * (piL * uL[D][f] + piR * uR[D][f]) - 0.5 * cf * (ER - EL);
    if constexpr (GRAN) fh[f] -= 0.5 * cf * (hR - hL);
  }
}

}  // namespace cosim::fluid
