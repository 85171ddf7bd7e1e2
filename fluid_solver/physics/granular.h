// Granular temperature of a dispersed particle phase (docs/methods.md §2.9): the kinetic energy of the particles'
// random motion about their mean velocity, k = 3/2 Theta per unit mass. A single-velocity particle field that meets
// a wall (or another stream) loses the kinetic energy of its normal motion; with k that energy is kept as random
// motion, whose pressure sends the particles back: the continuum form of particles bouncing off a wall. From the
// kinetic theory of granular flow (Lun, Savage, Jeffrey and Chepurniy 1984; Gidaspow 1994, ch. 9), with the
// radial distribution of Carnahan and Starling (1969):
//   granular pressure  p_g = alpha rho_p Theta F(alpha),   F = 1 + 2 (1 + e) alpha g0(alpha),
//   g0(alpha) = (1 - alpha/2) / (1 - alpha)^3,
//   collisional loss   gamma = 12 (1 - e^2) g0 alpha^2 rho_p Theta^(3/2) / (d sqrt(pi))   [W/m^3],
// e the restitution coefficient of particle collisions and d the particle diameter. g0 is held at its value of
// alpha_cp - delta above it, where the collision stress takes over (a rational g0, so that the face loops that
// evaluate it vectorise).
#pragma once

#include <algorithm>
#include <cmath>

namespace cosim::fluid {

struct GranularGas {
  bool enabled = true;
  double restitution = 0.9;  // e of particle-particle collisions
  double packing = 0.6;      // alpha_cp (the collision stress's)
  double delta = 0.01;       // g0 is frozen within delta of packing
  double diameter = 1e-4;    // [m]
  // Below this volume fraction the particles keep no random motion: its energy becomes the material's heat. A
  // granular gas expanding into a near vacuum of particles would otherwise send its last traces off at many times
  // its sound speed, and they would set the step.
  double alpha_min = 1e-5;

  [[gnu::always_inline]] inline double g0(double a) const {
    const double x = std::min(std::max(a, 0.0), packing - delta), r = 1.0 / (1.0 - x);
    return (1.0 - 0.5 * x) * r * r * r;
  }
  // p_g / (alpha rho_p Theta) and the squared wave speed per Theta, c_g^2 / Theta = 5/3 F + alpha F' (the
  // isentropic sound speed of the granular gas, Theta ~ alpha^(2/3) along an isentrope), at volume fraction a.
  [[gnu::always_inline]] inline void factors(double a, double& F, double& c2_per_theta) const {
    const double x = std::min(std::max(a, 0.0), packing - delta), r = 1.0 / (1.0 - x);
    const double g = (1.0 - 0.5 * x) * r * r * r, dg = (2.5 - x) * r * r * r * r;  // g0, dg0/dalpha
    F = 1.0 + 2.0 * (1.0 + restitution) * x * g;
    const double dF = 2.0 * (1.0 + restitution) * (g + x * dg);
    c2_per_theta = 5.0 / 3.0 * F + x * dF;
  }
  // Granular pressure (per mixture area, on the particle phase) and wave speed of a phase with volume fraction a,
  // material density rho and granular energy k per unit mass (k < 0, round-off of k = E - e - u^2/2, counts 0).
  [[gnu::always_inline]] inline void pressure_and_speed(double a, double rho, double k, double& pg, double& c) const {
    double F, c2;
    factors(a, F, c2);
    const double theta = std::max(k, 0.0) * (2.0 / 3.0);
    pg = a * rho * theta * F;
    c = std::sqrt(theta * c2);
  }
  // The granular energy per unit mass after dt of collisional loss alone (none below alpha_min), from the exact
  // solution of dTheta/dt = -c Theta^(3/2), c = 8 (1 - e^2) g0 alpha / (d sqrt(pi)).
  double after_collisions(double a, double k, double dt) const {
    if (a < alpha_min) return 0.0;
    if (!(k > 0.0)) return k;
    const double c = 8.0 * (1.0 - restitution * restitution) * g0(a) * a / (diameter * std::sqrt(M_PI));
    const double s = std::sqrt(k * (2.0 / 3.0));
    const double q = 1.0 + 0.5 * c * s * dt;
    return k / (q * q);
  }
};

}  // namespace cosim::fluid
